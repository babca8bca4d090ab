//! Depth order: a BSP tree built once for a static mesh, walked per viewpoint, or
//! Newell's depth sort made per view ([`NewellOrder`]) (Laszlo's and Dutt's notes on
//! hidden-surface removal).
//!
//! [`BspTree::build`] splits the mesh's faces into fragments so that every node's
//! plane has its subtrees' fragments strictly on one side each; it runs on an
//! explicit work stack in storage the caller lends ([`BspStorage`], sized with
//! [`BspSizes`]), with no recursion and no allocation. [`BspTree::rank_front_to_back`]
//! then ranks the fragments for a [`Viewpoint`](crate::Viewpoint), nearest first, in
//! one iterative walk: for any ray from the eye, the nearest fragment it meets has
//! the lowest rank among those it meets, and fragments at equal depth (coplanar)
//! rank by source face id, lower first ([conventions](crate::conventions): on equal depth the lower
//! face index wins). That order is what weight-1 surface codes need (the modulo-2
//! surface-filling paper).

mod bsp;
mod build;
mod depth_order;
mod newell;
mod plane;
mod seams;
#[cfg(test)]
mod tests;

pub use bsp::{
    work_bound, BspNode, BspOptions, BspSizes, BspStorage, BspTree, NO_NODE, PLANE_TOLERANCE,
};
pub use depth_order::DepthOrder;
pub use newell::{NewellOptions, NewellOrder, NewellSizes, NewellStorage};
pub(crate) use plane::is_planar;
pub use plane::planar_faces;
