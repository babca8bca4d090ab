//! Host-side checks for pbuffer: the f64 reference, random scene generators, images.
pub mod baseline;
pub mod bench3d;
pub mod callgrind;
pub mod cli;
pub mod fit;
pub mod frame;
pub mod image;
pub mod metrics;
pub mod obj;
pub mod orbit;
pub mod pipeline;
pub mod random;
pub mod reference;
pub mod reference3d;
pub mod report;
pub mod scenes;
pub mod shapes;
