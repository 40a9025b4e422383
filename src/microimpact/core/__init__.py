"""The physics core: one scalar source per formula and model (see the architecture page)."""
