// SPDX-License-Identifier: MIT
#pragma once
// Factories of the catalogue's scenes; each returns nullptr for a size the
// scene cannot take.
#include <memory>

#include "rewind/scenes/scene.h"

namespace rwd::scenes {

std::unique_ptr<Scene> make_stack(int boxes);
std::unique_ptr<Scene> make_far_stack(int distance_m);
std::unique_ptr<Scene> make_pyramid(int base);
std::unique_ptr<Scene> make_sleep(int base);
std::unique_ptr<Scene> make_mass_ratio(int ratio);
std::unique_ptr<Scene> make_kick(int boxes);
std::unique_ptr<Scene> make_card_house(int levels);
std::unique_ptr<Scene> make_free_fall(int seconds);
std::unique_ptr<Scene> make_bounce(int percent);
std::unique_ptr<Scene> make_slide(int speed);
std::unique_ptr<Scene> make_incline_stick(int degrees);
std::unique_ptr<Scene> make_incline_slip(int degrees);
std::unique_ptr<Scene> make_roll(int degrees);
std::unique_ptr<Scene> make_free_spin(int rate);
std::unique_ptr<Scene> make_projectile(int speed);
std::unique_ptr<Scene> make_pile(int count);
std::unique_ptr<Scene> make_mixed_pile(int count);
std::unique_ptr<Scene> make_log_cabin(int layers);
std::unique_ptr<Scene> make_hull_stack(int count);
std::unique_ptr<Scene> make_compound_balance(int count);
std::unique_ptr<Scene> make_hull_slip(int degrees);
std::unique_ptr<Scene> make_roll_stop(int tenths);
std::unique_ptr<Scene> make_convex_pile(int count);
std::unique_ptr<Scene> make_compound_pile(int count);
std::unique_ptr<Scene> make_mesh_pile(int count);
std::unique_ptr<Scene> make_field_boxes(int count);
std::unique_ptr<Scene> make_overlap(int count);
std::unique_ptr<Scene> make_crates(int players);

}  // namespace rwd::scenes
