//! 3-D frames against the f64 references: every engine, the fast engine, grey, the whole
//! pipeline, feature edges, open meshes, faces that are not planar, dashes along edges,
//! picking, the code schemes, the depth orders (BSP, Newell), the short API, scenes of
//! posed parts, depth precision, random views and hidden lines by the segment.
//!
//! One test binary; each module is one suite (`cargo test -p host_tests --test frames
//! MODULE::`).

mod bsp_order;
mod code_schemes;
mod dashes_along;
mod depth_precision;
mod engines_agree;
mod far_coordinates;
mod fast_vs_reference;
mod feature_edges;
mod grey_vs_reference;
mod line_test;
mod newell_order;
mod non_planar_faces;
mod open_mesh;
mod pick;
mod pipeline_vs_reference;
mod random_views;
mod scene_fit;
mod scene_union;
mod segment_lines;
mod short_api;
