//! Depth geometry that every engine, the line test and picking share: a face's
//! nearness plane ([`plane`]), the fan triangles of a face that is not planar
//! ([`fan`]), and which points and pixel centres a polygon covers ([`coverage`]).
//! It sits below the engines and the line pass in the flow: nothing here imports
//! from them.

pub(crate) mod coverage;
pub(crate) mod fan;
pub(crate) mod plane;
