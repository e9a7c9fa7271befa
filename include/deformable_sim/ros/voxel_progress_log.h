// How far a body's voxelization is, in the node's log: a line at each tenth once it has taken
// more than a second, so that a large grid does not stall the node's start without a word.
#pragma once

#include <functional>
#include <string>

namespace deformable_sim::ros_layer {

/// A progress callback for io::SurfaceSources::progress: (body, cells done, cells in all).
std::function<void(const std::string&, long, long)> voxelProgressLog();

}  // namespace deformable_sim::ros_layer
