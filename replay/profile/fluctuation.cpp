// The fluctuation model of a cell's amplitude (sensor_config.hpp `Fluctuation`) from the detection
// rate against SNR margin: a stationary detection seen at margin x (linear, over the threshold) in
// one cycle is seen again in the next with a probability that depends on how the amplitude
// fluctuates. With a scale-free prior on the mean SNR u (p(u) ~ 1/u) the posterior after seeing x:
//   Swerling 1 (x = u E, E ~ Exp(1)):           P = x / (1 + x)
//   Swerling 3 (x = u G, G ~ Gamma(2, rate 2)):  P = (x / (1 + x))^2 + 2 x^2 / (1 + x)^3
//   steady (Swerling 0, pointer noise only):     P = Phi(margin_dB / 1.5 dB)
// Matching loses some detections whatever the model (the scatterer's aspect, occlusion), so each
// curve is scaled by its own least-squares plateau q <= 1, and the model with the least residual is
// taken. On the aiMotive drive the rate rises more slowly than any of the three (0.07 at 1 dB,
// 0.45 at 9 dB, 0.8 above 20 dB: glints as the ego passes, the peak search): Swerling 1, the
// heaviest, fits best, with its residual in the evidence.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "common/decibel.hpp"
#include "replay/profile/derivation_stages.hpp"

namespace rcsim::replay::profile {
namespace {

constexpr double kBinDb = 2.0;
constexpr std::size_t kMinPerBin = 30;
constexpr double kSteadySpreadDb = 1.5;  // a steady amplitude's spread from the pointer noise at the threshold

struct Model {
  const char* name;
  double (*redetection)(double margin_db);
};

double swerling1(double margin_db) {
  const double x = db_to_power(margin_db);
  return x / (1.0 + x);
}
double swerling3(double margin_db) {
  const double x = db_to_power(margin_db);
  return std::pow(x / (1.0 + x), 2) + 2.0 * x * x / std::pow(1.0 + x, 3);
}
double steady(double margin_db) { return 0.5 * std::erfc(-margin_db / kSteadySpreadDb / std::sqrt(2.0)); }

constexpr std::array<Model, 3> kModels{{{"none", steady}, {"swerling1", swerling1}, {"swerling3", swerling3}}};

struct Bin {
  double margin_db = 0.0, rate = 0.0;
  std::size_t n = 0;
};

struct Fit {
  double plateau = 1.0, rms = INFINITY;
};

Fit fit(const Model& m, const std::vector<Bin>& bins) {
  double rp = 0.0, pp = 0.0;
  for (const Bin& b : bins) {
    const double p = m.redetection(b.margin_db);
    rp += static_cast<double>(b.n) * b.rate * p, pp += static_cast<double>(b.n) * p * p;
  }
  Fit f;
  f.plateau = std::min(1.0, rp / pp);
  double sum = 0.0, total = 0.0;
  for (const Bin& b : bins) {
    sum += static_cast<double>(b.n) * std::pow(b.rate - f.plateau * m.redetection(b.margin_db), 2);
    total += static_cast<double>(b.n);
  }
  f.rms = std::sqrt(sum / total);
  return f;
}

}  // namespace

std::vector<DerivedValue> derive_fluctuation(const std::vector<FramePair>& frame_pairs, bool snapshots,
                                             std::vector<DerivationFigure>& figures) {
  std::map<int, std::pair<std::size_t, std::size_t>> seen_of;  // 2-dB bin -> (seen again, seen)
  std::size_t observations = 0;
  for (const FramePair& pair : frame_pairs) {
    for (const Redetection& r : pair.redetections) {
      auto& [again, all] = seen_of[static_cast<int>(std::floor(std::max(0.0, r.margin_db) / kBinDb))];
      again += r.seen ? 1 : 0, ++all, ++observations;
    }
  }
  std::vector<Bin> bins;
  for (const auto& [bin, counts] : seen_of) {
    if (counts.second >= kMinPerBin) {
      bins.push_back({kBinDb * (bin + 0.5), static_cast<double>(counts.first) / static_cast<double>(counts.second), counts.second});
    }
  }
  // The models part below about 10 dB of margin: the bins must reach from near the threshold to
  // well above it.
  if (bins.size() < 4 || bins.front().margin_db > 4.0 || bins.back().margin_db < 14.0) {
    const std::string why = snapshots ? "not observable: single frames, none follows another"
                                      : fmt::format("too few stationary detections matched from cycle to cycle ({} in {} bins of "
                                                    "{:.0f} dB with {} or more)",
                                                    observations, bins.size(), kBinDb, kMinPerBin);
    return {{"detection.fluctuation", nullptr, ValueSource::base, why, 0}};
  }
  std::array<Fit, kModels.size()> fits;
  std::size_t best = 0;
  for (std::size_t m = 0; m < kModels.size(); ++m) {
    fits[m] = fit(kModels[m], bins);
    if (fits[m].rms < fits[best].rms) best = m;
  }
  DerivationFigure figure{"Re-detection in the next cycle against the SNR margin it was seen at", "amplitude - threshold / dB",
                          "fraction seen again", "stationary detections matched after the ego's motion, per 2-dB bin; each "
                          "model scaled by its plateau (matching losses)",
                          {}};
  FigureSeries measured{"measured", true, {}};
  for (const Bin& b : bins) measured.points.emplace_back(b.margin_db, b.rate);
  figure.series.push_back(measured);
  for (std::size_t m = 0; m < kModels.size(); ++m) {
    FigureSeries curve{fmt::format("{} (RMS {:.3f})", kModels[m].name, fits[m].rms), false, {}};
    for (double margin_db = 0.0; margin_db <= bins.back().margin_db + kBinDb; margin_db += 0.5) {
      curve.points.emplace_back(margin_db, fits[m].plateau * kModels[m].redetection(margin_db));
    }
    figure.series.push_back(std::move(curve));
  }
  figures.push_back(std::move(figure));
  std::string others;
  for (std::size_t m = 0; m < kModels.size(); ++m) {
    if (m != best) others += fmt::format("{}{} {:.3f}", others.empty() ? "" : ", ", kModels[m].name, fits[m].rms);
  }
  // A word has no interval; it is weak where another model fits within 10 % of the best's RMS.
  bool close = false;
  for (std::size_t m = 0; m < kModels.size(); ++m) close = close || (m != best && fits[m].rms < 1.1 * fits[best].rms);
  DerivedValue value{"detection.fluctuation", kModels[best].name, ValueSource::derived,
                     fmt::format("{} stationary detections followed to the next cycle: seen again {:.2f} at {:.0f} dB over the threshold, "
                                 "{:.2f} at {:.0f} dB; {} fits best (RMS {:.3f}, plateau {:.2f}; {}){}",
                                 observations, bins.front().rate, bins.front().margin_db, bins.back().rate, bins.back().margin_db,
                                 kModels[best].name, fits[best].rms, fits[best].plateau, others,
                                 close ? "; weak: another model fits within 10 %" : ""),
                     static_cast<long long>(observations)};
  value.weak = close;
  return {value};
}

}  // namespace rcsim::replay::profile
