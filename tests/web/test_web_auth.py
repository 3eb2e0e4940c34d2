"""Login, sessions, CSRF and tokens; every /api route of the OpenAPI document needs auth."""

from __future__ import annotations

import re

from fastapi.testclient import TestClient
from web_served import PASSWORD, TOKEN, login

from amiro.web.auth import hash_password, verify_password


def test_password_hash_is_salted_scrypt_and_verifies() -> None:
    a, b = hash_password("secret"), hash_password("secret")
    assert a != b and a.startswith("scrypt$") and "secret" not in a
    assert verify_password("secret", a) and not verify_password("Secret", a)
    assert not verify_password("secret", "garbage")


def test_login_session_and_csrf(client: TestClient) -> None:
    assert client.get("/healthz").status_code == 200
    bad = client.post("/auth/login", json={"user": "admin", "password": "nope"})
    assert bad.status_code == 401 and "amiro_session" not in client.cookies
    assert client.get("/api/me").status_code == 401
    csrf = login(client)
    cookie = client.cookies.get("amiro_session")
    assert cookie and PASSWORD not in cookie
    assert client.get("/api/me").json() == {"user": "admin", "csrf": csrf}
    body = {"text": "hello", "lang": "en"}
    assert client.post("/api/chat", json=body).status_code == 403
    assert (
        client.post("/api/chat", json=body, headers={"X-CSRF-Token": "x" + csrf}).status_code == 403
    )
    assert client.post("/api/chat", json=body, headers={"X-CSRF-Token": csrf}).status_code == 200
    client.cookies.clear()  # else the jar keeps the real cookie beside the tampered one
    client.cookies.set("amiro_session", cookie)
    assert client.get("/api/me").status_code == 200  # a cookie set this way is sent
    client.cookies.clear()
    client.cookies.set("amiro_session", cookie[:-3] + "abc")  # tampered signature
    assert client.get("/api/me").status_code == 401


def test_bearer_token_for_scripts(client: TestClient) -> None:
    auth = {"Authorization": f"Bearer {TOKEN}"}
    assert client.get("/api/state", headers=auth).status_code == 200
    assert client.get("/api/state", headers={"Authorization": "Bearer wrong"}).status_code == 401
    res = client.post("/api/chat", json={"text": "hi"}, headers=auth)
    assert res.status_code == 200  # no cookie, so no CSRF token needed


def test_every_api_route_in_openapi_answers_401_without_auth(client: TestClient) -> None:
    doc = client.get("/openapi.json").json()
    routes = [(path, method) for path, ops in doc["paths"].items() for method in ops]
    api_routes = [(p, m) for p, m in routes if p.startswith("/api")]
    assert len(api_routes) >= 12
    assert {p for p, _ in routes if not p.startswith("/api")} == {
        "/healthz",
        "/auth/login",
        "/auth/logout",
    }
    for path, method in api_routes:
        url = re.sub(r"\{[^}]+\}", "maria", path)
        for headers in ({}, {"Authorization": "Bearer wrong"}, {"Cookie": "amiro_session=forged"}):
            res = client.request(method.upper(), url, json={}, headers=headers)
            assert res.status_code == 401, (method, path, headers, res.status_code)
