"""Built-in scene files (TOML); see docs/scenes.md."""
