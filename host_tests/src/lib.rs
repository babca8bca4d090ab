//! Host-side checks for pbuffer: the f64 reference, random scene generators, images.
pub mod image;
pub mod random;
pub mod reference;
pub mod scenes;
