"""One module per mechanism; each defines `SPEC` (a `mechkit.catalog.registry.MechanismSpec`)."""
