//! MTL material libraries for OBJ (not yet written).
