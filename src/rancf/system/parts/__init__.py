"""The physical items of a system, one module a kind, each a :class:`rancf.system.part.Part`."""
