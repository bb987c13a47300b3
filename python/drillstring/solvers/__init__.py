"""Solvers of the paper's model: the modal (Galerkin) solve, the PDE solve and their results."""
