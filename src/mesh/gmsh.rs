//! Gmsh MSH reader (to be written).
