"""The study server: FastAPI app, participant flow, websocket protocol, game loop, robot workers, settings, and the
`steakhouse` command line (which also runs the export and analysis of `analysis/`). The SQL store is `store/`."""
