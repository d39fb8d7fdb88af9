"""Package data: the URDF of every registered mechanism at its default parameters (generated)."""
