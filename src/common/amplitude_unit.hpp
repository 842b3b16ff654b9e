#pragma once
// What a radar's amplitudes are (docs/amplitude.md), for recordings and sensor profiles alike: an
// SNR in dB (the radar equation's scale), or a level in dB on the radar's own scale that need not
// fall with range as the radar equation says (a range-compensated amplitude such as the Astyx
// HiRes's `Mag`).
namespace rcsim {

enum class AmplitudeUnit { snr_db, relative_db };

}  // namespace rcsim
