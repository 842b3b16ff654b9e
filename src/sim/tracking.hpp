#pragma once
// Sensor-internal tracking (paper III-E): a linear Kalman filter over the target-list variables
// (range, range rate, azimuth, amplitude), gated global-nearest-neighbour association, 4-hit
// confirmation, deletion after misses. Roles kept apart as in Stone Soup: predictor, gater and
// associator, updater (Joseph form), initiator, deleter. Tentative tracks stay in the table.
#include <Eigen/Core>
#include <vector>

#include "sensor/sensor_config.hpp"
#include "sim/stage_types.hpp"

namespace rcsim {

using TrackState = Eigen::Vector4d;       // [range_m, range_rate_mps, azimuth_rad, amplitude_db]
using TrackCovariance = Eigen::Matrix4d;

enum class TrackStatus : std::uint8_t { Tentative, Confirmed };

struct Track {
  int id = 0;
  TrackStatus status = TrackStatus::Tentative;
  int hits = 0;             // measurements assigned so far
  int misses = 0;           // consecutive cycles without one
  int age_cycles = 0;
  bool updated = false;     // got a measurement this cycle
  int object_index = -1;    // truth of the last assigned detection (for metrics, never for tracking)
  TrackState x = TrackState::Zero();
  double elevation_rad = 0.0;  // a radar that measures elevation: its last detection's (not filtered)
  TrackCovariance P = TrackCovariance::Identity();
};

// Kalman predictor: constant range rate, random-walk azimuth and amplitude.
struct KalmanModel {
  Eigen::Matrix4d F;
  Eigen::Matrix4d Q;
  Eigen::Matrix4d R;
  KalmanModel(const TrackerConfig& config, double cycle_time_s);
};

void kalman_predict(const KalmanModel& model, Track& track);
// Innovation z - H x with the azimuth difference wrapped.
Eigen::Vector4d innovation(const Track& track, const Detection& detection);
// Squared Mahalanobis distance of an innovation, nu' (P + R)^-1 nu.
double mahalanobis2(const KalmanModel& model, const Track& track, const Eigen::Vector4d& nu);
// Joseph-form update (H = I), covariance kept symmetric.
void kalman_update(const KalmanModel& model, const Detection& detection, Track& track);

// Fidelity::no_tracking: every detection becomes a reported target, id = its row index.
void report_detections_directly(const Detections& detections, ReportedTargets& reported);

class Tracker {
 public:
  Tracker(const TrackerConfig& config, double cycle_time_s);

  // One cycle: predict, associate, update, initiate, delete; then the confirmed tracks updated
  // this cycle into `reported` (ordered by track id).
  void step(const Detections& detections, ReportedTargets& reported);
  const std::vector<Track>& tracks() const { return tracks_; }
  long long dropped_initiations() const { return dropped_initiations_; }

 private:
  struct Candidate {
    double distance2;
    int track;
    int detection;
  };
  struct RangeEntry {
    double range_m;
    int detection;
  };
  void predict();
  void associate(const Detections& detections);
  void initiate(const Detections& detections);
  void confirm_if_due(Track& track) const;  // the M-of-N initiator's confirmation rule
  void delete_stale();

  TrackerConfig config_;
  KalmanModel model_;
  std::vector<Track> tracks_;
  std::vector<Candidate> candidates_;
  std::vector<RangeEntry> detections_by_range_;
  std::vector<char> detection_taken_;
  int next_id_ = 1;
  long long dropped_initiations_ = 0;
};

}  // namespace rcsim
