//! Built-in meshes (to be written).
