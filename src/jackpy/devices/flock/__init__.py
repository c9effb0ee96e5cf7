"""Ascension Flock of Birds: protocol (pure), pyserial driver, and a pseudo-terminal simulator."""
