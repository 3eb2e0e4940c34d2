"""The ``web:`` config section of ``amiro serve``."""

from __future__ import annotations

from pydantic import Field, SecretStr

from amiro.core.config import Section


class WebConfig(Section):
    host: str = "127.0.0.1"
    port: int = Field(default=8080, ge=0, le=65535)
    admin_user: str = "admin"
    admin_password: SecretStr | None = Field(
        default=None, description="else AMIRO_ADMIN_PASSWORD; stored only as a scrypt hash"
    )
    api_token: SecretStr | None = Field(
        default=None, description="a bearer token for scripts (else AMIRO_API_TOKEN)"
    )
    session_max_age_s: int = Field(default=12 * 3600, gt=0)
    secure_cookies: bool = Field(default=False, description="set behind HTTPS")
    demo_data: bool = Field(
        default=True,
        description="seed 14 days of demo health data (marked as demo) into an in-memory "
        "health store; never into a database",
    )
    state_period_s: float = Field(default=0.2, gt=0.0, description="wall s between map updates")
