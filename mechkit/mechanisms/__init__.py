"""One module per mechanism; each defines `SPEC` (a `mechkit.registry.MechanismSpec`)."""
