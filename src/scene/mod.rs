//! Scenes: several rigid parts, each a mesh baked once and a pose that may change
//! every frame, drawn as one frame with mutual hiding ([`SceneDrawing`]).
//!
//! # What a scene's frame is
//! The frame of a scene is the frame of its **union mesh**: the instances'
//! vertices, each posed by its instance's [`Pose`] ([`Pose::apply`], in `f32`),
//! one after the other in instance order, and their faces numbered the same way,
//! so that face `f` of instance `k` is face `f + (faces of instances 0..k)` of the
//! union and the `--ids` of a scene are the union's.
//!
//! **Feature edges are classified per mesh.** Each instance keeps the edges it
//! was baked with: vertices weld only within an instance, and a crease or a
//! silhouette never joins two instances, even where two instances touch or their
//! posed vertices coincide bit for bit. A face's facing is its instance's: the
//! baked normal and centroid tested against the eye brought into the instance's
//! space (`R^T (eye - t)`), which in exact arithmetic is the posed face's test; in
//! `f32` the two may differ only for a face seen edge-on, within rounding. A
//! face's planarity is its instance's (kept bits, else taken as planar).
//! `Cull::Auto` culls when every instance is closed.
//!
//! Everything else (hiding, dashes, ties: the lower face index wins) is the union
//! mesh's, as [conventions](crate::conventions) define it for one mesh. The
//! `render` command's `--dump-obj` writes that union as one OBJ.
//!
//! # What a frame costs per instance
//! Per frame, a pose costs what it must: each vertex posed (nine multiplies and
//! nine adds) and checked finite, the eye brought into each instance's space once,
//! and a facing test per face on the baked plane, as for one mesh. Nothing is
//! derived from the meshes again. What stays fixed while poses change (the
//! union's corner indices, planes, planarity bits and edges) is assembled in RAM
//! when an instance is added.

mod drawing;
mod pose;
#[cfg(test)]
mod tests;

pub use drawing::SceneDrawing;
pub use pose::Pose;
