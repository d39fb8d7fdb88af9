"""Independent validators written with numpy/scipy only (no Pinocchio dynamics)."""
