"""The study server: FastAPI app, websocket protocol, game loop, SQL store, settings, and the CLI."""
