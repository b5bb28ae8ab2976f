"""Live trials: the participant's controller, the per-tick engine, FOV masking, the asyncio game loop and
the registry of live games."""
