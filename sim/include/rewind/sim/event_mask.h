// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

namespace rwd::sim {

/// Which contact events a body asks for (BodyDef::event_mask,
/// World3D::set_event_mask): one bit per event type, for solid contacts
/// and for sensor (trigger) overlaps apart. A pair's event is reported
/// when either body's mask has its bit.
using EventMask = uint8_t;

inline constexpr EventMask kEventNone = 0;
inline constexpr EventMask kEventContactEnter = 1u << 0;  ///< two solid bodies start touching
inline constexpr EventMask kEventContactStay = 1u << 1;   ///< and keep touching
inline constexpr EventMask kEventContactExit = 1u << 2;   ///< and stop touching
inline constexpr EventMask kEventSensorEnter = 1u << 3;   ///< a sensor starts overlapping a body
inline constexpr EventMask kEventSensorStay = 1u << 4;    ///< and keeps overlapping it
inline constexpr EventMask kEventSensorExit = 1u << 5;    ///< and stops overlapping it
inline constexpr EventMask kEventContactAll =
    kEventContactEnter | kEventContactStay | kEventContactExit;
inline constexpr EventMask kEventSensorAll =
    kEventSensorEnter | kEventSensorStay | kEventSensorExit;
/// Every event: what a body reports unless told otherwise.
inline constexpr EventMask kEventAll = kEventContactAll | kEventSensorAll;

}  // namespace rwd::sim
