"""Files, progress, the verified sweep store and cluster helpers (internal)."""
