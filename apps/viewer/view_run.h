/// @file
/// habuffer-view's run: the window, the scene, the session, and the frame
/// loop with its inputs, panel, overlay and scripted steps; then the last
/// frame's files (screenshot, window shot, report).
#pragma once

#include "view_command.h"

namespace habuffer::view {

/// Runs the viewer; returns the exit code (0; 1 when a scripted technique
/// switch was refused or a GL error was seen). Throws for bad data (scene,
/// GL limits, no window): main prints it.
int run_view(const ViewSettings& settings);

}  // namespace habuffer::view
