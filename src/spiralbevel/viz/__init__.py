"""Matplotlib plots. Every function imports matplotlib lazily and returns a Figure; nothing here computes geometry."""
