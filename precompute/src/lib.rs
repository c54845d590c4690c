//! Host precompute for eigenrad: scene in; form factors, eigenbasis, serialized basis and an
//! accuracy report out. The `eigenrad` command is a thin layer over this library.
pub mod eigen;
pub mod formfactor;
pub mod geometry;
pub mod scene;
pub mod solve;
