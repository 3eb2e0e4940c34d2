"""The dashboard's FastAPI app: public pages and login, the guarded ``/api``, a websocket.

One middleware guards every ``/api`` route (so a route cannot forget it): no valid session
cookie or bearer token → 401; a cookie-authenticated unsafe method without the session's
CSRF token → 403.  Responses are counted by status, so fuzzing shows what was rejected.
"""

from __future__ import annotations

import asyncio
import hmac
from collections import Counter
from collections.abc import Awaitable, Callable
from importlib import resources
from pathlib import Path
from typing import Any

from fastapi import FastAPI, Request, Response, WebSocket, WebSocketDisconnect
from fastapi.exceptions import RequestValidationError
from fastapi.responses import FileResponse, JSONResponse
from fastapi.staticfiles import StaticFiles

from amiro import __version__
from amiro.web.api import Backend, build_router
from amiro.web.auth import COOKIE, CSRF_HEADER, Authenticator, LoginThrottle
from amiro.web.config import WebConfig
from amiro.web.models import LoginBody

SAFE_METHODS = {"GET", "HEAD", "OPTIONS"}


def static_dir() -> Path:
    return Path(str(resources.files("amiro.web").joinpath("static")))


def create_app(backend: Backend, auth: Authenticator, config: WebConfig) -> FastAPI:
    app = FastAPI(title="amiro dashboard", version=__version__, docs_url=None, redoc_url=None)
    stats: Counter[str] = Counter()
    app.state.stats = stats
    static = static_dir()

    @app.middleware("http")
    async def guard(
        request: Request, call_next: Callable[[Request], Awaitable[Response]]
    ) -> Response:
        response = await _guarded(request, call_next)
        stats[f"{response.status_code // 100}xx"] += 1
        stats["requests"] += 1
        return response

    async def _guarded(
        request: Request, call_next: Callable[[Request], Awaitable[Response]]
    ) -> Response:
        request.state.session = None
        request.state.user = None
        if not request.url.path.startswith("/api"):
            return await call_next(request)
        session = auth.session(request.cookies.get(COOKIE))
        if session is not None:
            sent = request.headers.get(CSRF_HEADER, "")
            if request.method not in SAFE_METHODS and not hmac.compare_digest(
                sent.encode(), session.csrf.encode()
            ):
                return JSONResponse({"detail": "missing or wrong CSRF token"}, 403)
            request.state.session, request.state.user = session, session.user
        elif auth.token_ok(request.headers.get("authorization")):
            request.state.user = "token"
        else:
            return JSONResponse(
                {"detail": "authentication required"}, 401, {"WWW-Authenticate": "Bearer"}
            )
        return await call_next(request)

    @app.exception_handler(RequestValidationError)
    async def invalid(_request: Request, exc: RequestValidationError) -> JSONResponse:
        first = exc.errors()[0] if exc.errors() else {}
        where = ".".join(str(p) for p in first.get("loc", ()))
        return JSONResponse({"detail": f"{where}: {first.get('msg', 'invalid input')}"}, 422)

    @app.get("/healthz")
    def healthz() -> dict[str, Any]:
        return {"ok": True, "version": __version__}

    throttle = LoginThrottle()

    @app.post("/auth/login")
    def login(body: LoginBody, request: Request) -> JSONResponse:
        client = request.client.host if request.client else "?"
        if throttle.blocked(client):
            stats["login_throttled"] += 1
            return JSONResponse({"detail": "too many failed logins; wait a minute"}, 429)
        cookie = auth.login(body.user, body.password)
        session = auth.session(cookie)
        if cookie is None or session is None:
            stats["login_failed"] += 1
            throttle.failed(client)
            return JSONResponse({"detail": "wrong user or password"}, 401)
        response = JSONResponse({"user": session.user, "csrf": session.csrf})
        response.set_cookie(
            COOKIE,
            cookie,
            max_age=config.session_max_age_s,
            httponly=True,
            samesite="strict",
            secure=config.secure_cookies,
        )
        return response

    @app.post("/auth/logout")
    def logout(response: Response) -> dict[str, Any]:
        response.delete_cookie(COOKIE)
        return {"ok": True}

    @app.get("/", include_in_schema=False)
    def index() -> FileResponse:
        return FileResponse(static / "index.html")

    @app.get("/login", include_in_schema=False)
    def login_page() -> FileResponse:
        return FileResponse(static / "login.html")

    @app.websocket("/ws")
    async def live(ws: WebSocket) -> None:
        if auth.session(ws.cookies.get(COOKIE)) is None:
            await ws.close(code=1008)
            return
        await ws.accept()
        try:
            while True:
                await ws.send_json(backend.gateway.snapshot)
                await asyncio.sleep(config.state_period_s)
        except (WebSocketDisconnect, RuntimeError):
            return

    app.include_router(build_router(backend))
    app.mount("/static", StaticFiles(directory=static), name="static")
    return app
