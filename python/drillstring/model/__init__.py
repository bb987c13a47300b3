"""The paper's model: parameters, cross-sections, the coefficients k1..k6 and the Galerkin projection."""
