"""Bundled example designs (TOML)."""
