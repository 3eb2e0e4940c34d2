"""The web dashboard: FastAPI app, its auth, the gateway into the runtime and static files."""
