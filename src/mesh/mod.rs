//! Meshes borrowed from the caller, validated once; edge adjacency and feature edges.
