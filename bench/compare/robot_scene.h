#pragma once

// The arm scene "arm:B" or "arm:B:L" (issue 66's comparison), described once for every engine: the
// test robot (examples/robot_arm: a pan, a lift and an elbow joint and two sliding fingers,
// covered by 60 certified spheres) bolted to the plane beside a pile of B small bunnies (12 cm,
// depth-3 trees), stepped at 1 kHz for 10 s while its position control follows a motion that
// reaches over the pile and sweeps its hand across the pile one way, with the shoulder lifted by L
// (0.9 rad, brushing the pile's top, unless given; up to 1.1 rad, through its upper layer), then
// higher back the other way. The arm and the pile stand on the plane as they would on a table.
//
// "arm-drag:M": the same arm and motion (the shoulder lifted by 1.0 rad) with one 15 cm bunny of
// M kg lying across the hand's path 0.45 m from the base: how heavy a bunny each engine's arm
// drags aside at its effort, and what its joints do when it cannot.

#include <string>

#include "bench_scene.h"

namespace sphys::compare {

// True for a name of an arm scene ("arm:..." or "arm-drag:..."), well formed or not.
[[nodiscard]] bool is_robot_scene(const std::string& name);

// The scene the name describes. Throws sphys::Error naming the scene and its valid form for a
// malformed name or a count out of range.
[[nodiscard]] BenchScene make_robot_scene(const std::string& name);

}  // namespace sphys::compare
