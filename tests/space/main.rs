//! Arms in space as a specification: the presets' tasks, the spatial
//! planner, and the planar arm as a chain whose axes are parallel.

mod atlas;
mod kinematics;
mod lab;
mod modern;
mod planner;
