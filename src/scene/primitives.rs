//! Generated geometry: X3D primitives and benchmark meshes (not yet written).
