#pragma once
// One radar per sensor profile (docs/synth.md, "One radar per profile"): the reference design of
// synth_config.hpp (a 24 GHz short-range radar, srr24's facts) adapted to what a scene's sensor
// profile states about the radar itself — carrier, range and range-rate resolution, field of
// view and range, the receive pair, cycle time, confirmation, what it reports, on which scale its
// amplitude reads — through the FMCW relations. Never the profile's fitted model values (its
// amplitude law's constants, ERCS, noise): the reference stays independent of the model.
// A profile the reference cannot be made into is refused by name; so is a scene whose sensors
// cannot share one recording (schemas/recording.md: one cycle clock, one targets.csv).
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "synth/synth_config.hpp"

namespace rcsim::synth {

// The design adapted to one profile; for srr24 the design itself, bit for bit. Throws
// std::invalid_argument naming the profile and what cannot be synthesised.
SynthConfig sensor_design(const SensorConfig& profile, const SynthConfig& design);

// sensor_design for every sensor of the scene, in order; a refusal names the sensor's id and profile.
std::vector<SynthConfig> sensor_designs(const Scene& scene, const SynthConfig& design);

// What `rcsim synth` needs beyond sensor_designs to write one recording: every sensor runs at its
// own profile's cycle time, which is the scene's cycle time (one cycle clock), and all sensors
// report at one level (targets.csv has one id column). Throws std::invalid_argument naming the
// sensors and their cycle times (or levels).
void require_one_recording(const Scene& scene, const SynthConfig& design);

// The post-FFT SNR in dB of the unit scatterer on boresight in free space at a range (radar
// equation, IF filters, the windows' processing gain): what the link budget is sized by.
double unit_scatterer_snr_db(const SynthConfig& config, double range_m);

}  // namespace rcsim::synth
