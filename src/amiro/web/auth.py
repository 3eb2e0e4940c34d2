"""Passwords (scrypt), signed session cookies (itsdangerous) and CSRF tokens.

The session cookie holds the user and a per-session CSRF token, signed and time-stamped;
it is HttpOnly and SameSite=Strict.  Every state-changing request made with the cookie must
echo the token in the ``X-CSRF-Token`` header, which another site cannot read.  Scripts may
use ``Authorization: Bearer <token>`` instead (no cookie, so no CSRF exposure).
"""

from __future__ import annotations

import base64
import hashlib
import hmac
import secrets
import time
from collections import defaultdict, deque
from dataclasses import dataclass

from itsdangerous import BadSignature, URLSafeTimedSerializer

SCRYPT = {"n": 2**14, "r": 8, "p": 1}
COOKIE = "amiro_session"
CSRF_HEADER = "x-csrf-token"


def hash_password(password: str, salt: bytes | None = None) -> str:
    salt = salt if salt is not None else secrets.token_bytes(16)
    digest = hashlib.scrypt(password.encode(), salt=salt, dklen=32, **SCRYPT)
    b64 = base64.b64encode
    return f"scrypt${SCRYPT['n']}${b64(salt).decode()}${b64(digest).decode()}"


def verify_password(password: str, stored: str) -> bool:
    try:
        scheme, n, salt64, digest64 = stored.split("$")
        salt, digest = base64.b64decode(salt64), base64.b64decode(digest64)
        if scheme != "scrypt":
            return False
        got = hashlib.scrypt(password.encode(), salt=salt, n=int(n), r=8, p=1, dklen=len(digest))
    except (ValueError, TypeError):
        return False
    return hmac.compare_digest(got, digest)


@dataclass(frozen=True)
class Session:
    user: str
    csrf: str


class Authenticator:
    def __init__(
        self,
        user: str,
        password_hash: str,
        secret_key: str,
        max_age_s: int,
        api_token: str | None = None,
    ) -> None:
        self.user = user
        self.password_hash = password_hash
        self.max_age_s = max_age_s
        self.api_token = api_token
        self._signer = URLSafeTimedSerializer(secret_key, salt="amiro-session")

    def login(self, user: str, password: str) -> str | None:
        """A new session cookie value, or None for wrong credentials."""
        user_ok = hmac.compare_digest(user.encode(), self.user.encode())
        if not (verify_password(password, self.password_hash) and user_ok):
            return None
        return str(self._signer.dumps({"u": self.user, "c": secrets.token_urlsafe(24)}))

    def session(self, cookie: str | None) -> Session | None:
        if not cookie:
            return None
        try:
            data = self._signer.loads(cookie, max_age=self.max_age_s)
        except BadSignature:
            return None
        if not isinstance(data, dict) or data.get("u") != self.user:
            return None
        return Session(str(data["u"]), str(data.get("c", "")))

    def token_ok(self, authorization: str | None) -> bool:
        if self.api_token is None or not authorization:
            return False
        scheme, _, token = authorization.partition(" ")
        return scheme.lower() == "bearer" and hmac.compare_digest(
            token.encode(), self.api_token.encode()
        )


class LoginThrottle:
    """At most ``limit`` failed logins per client per ``window_s`` of real time.

    This guards the HTTP boundary against password guessing, so it counts wall time (the
    runtime clock may be simulated); a blocked attempt costs no password hashing.
    """

    def __init__(self, limit: int = 10, window_s: float = 60.0) -> None:
        self.limit = limit
        self.window_s = window_s
        self._failures: defaultdict[str, deque[float]] = defaultdict(deque)

    def _recent(self, client: str) -> deque[float]:
        times = self._failures[client]
        cutoff = time.monotonic() - self.window_s
        while times and times[0] < cutoff:
            times.popleft()
        return times

    def blocked(self, client: str) -> bool:
        return len(self._recent(client)) >= self.limit

    def failed(self, client: str) -> None:
        self._recent(client).append(time.monotonic())
