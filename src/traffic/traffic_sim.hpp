#pragma once
// The microscopic traffic simulation: every vehicle, the ego included, follows its leader by the
// IDM and changes lanes by MOBIL; on the intersection a conflict-area rule lets vehicles of only
// one road at a time into the shared square. Time advances in fixed steps by the ballistic update
// of Treiber & Kanagaraj (2015); the world motion of every vehicle is sampled for the scene.
#include <optional>
#include <string>
#include <vector>

#include "common/rng.hpp"
#include "scene/trajectory.hpp"
#include "traffic/road.hpp"
#include "traffic/traffic_config.hpp"

namespace rcsim::traffic {

enum class CrossingState { None, Approaching, Requested, Granted, Cleared };

struct Vehicle {
  std::string id;  // "ego", "car12", "truck3"
  int vehicle_class = 0;
  IdmParameters idm;  // with this vehicle's drawn desired speed
  double length_m = 0.0;
  double width_m = 0.0;
  int road = 0;
  double s_m = 0.0;        // centre of the box along the road's reference line
  double speed_mps = 0.0;  // ds/dt
  double accel_mps2 = 0.0; // applied in the last step
  int lane = 0;            // the lane it is in, or is changing into
  int from_lane = -1;      // while changing: the lane it leaves (it occupies both)
  double change_progress = 0.0;  // 0..1 along the lane-change path
  double change_length_m = 0.0;  // road length over which the lateral move happens
  double next_change_allowed_s = 0.0;
  bool active = true;
  bool is_ego = false;
  double enter_t_s = 0.0;
  double leave_t_s = 0.0;
  CrossingState crossing = CrossingState::None;
  double request_t_s = 0.0;

  bool changing() const { return from_lane >= 0; }
};

struct LaneChangeEvent {
  double t_s = 0.0;
  std::string vehicle;
  int from_lane = 0;
  int to_lane = 0;
  double new_follower_after_mps2 = 0.0;  // a~_n by the IDM with the gap at the decision (0: none)
  double changer_after_mps2 = 0.0;       // a~_c
  double advantage_mps2 = 0.0;
  // The gap the new follower gets, recomputable by the test from the raw IDM: its speed,
  // gap and approach rate, and its IDM parameters.
  bool has_new_follower = false;
  IdmParameters new_follower_idm;
  double new_follower_speed_mps = 0.0;
  double new_follower_gap_m = 0.0;
  double new_follower_approach_mps = 0.0;
};

// One vehicle's world state at a step (record_steps): for the tests.
struct VehicleSnapshot {
  int vehicle = 0;  // index into vehicles()
  WorldMotion motion;
  double s_m = 0.0;
  double d_m = 0.0;
  double speed_mps = 0.0;
  double accel_mps2 = 0.0;
  bool inside_conflict_area = false;
};
struct StepSnapshot {
  double t_s = 0.0;
  std::vector<VehicleSnapshot> vehicles;
};

// A vehicle's scene trajectory (samples from its entry to its exit or the scene's end).
struct VehicleTrack {
  std::string id;
  std::string model;
  bool is_ego = false;
  std::optional<double> present_from_s;
  std::optional<double> present_until_s;
  std::vector<TrajectorySample> samples;
};

class TrafficSimulation {
 public:
  // config must come from resolve_traffic_config. Draws the initial traffic from rng.
  TrafficSimulation(const TrafficConfig& config, Rng& rng);

  // Advances one step of config.step_s; arrivals and desired speeds are drawn from rng.
  void step(Rng& rng);
  // Runs from -warmup to duration_s, sampling the trajectories.
  void run(Rng& rng);

  double time_s() const { return static_cast<double>(step_index_) * config_.step_s - config_.warmup_s; }
  const TrafficConfig& config() const { return config_; }
  const std::vector<Road>& roads() const { return roads_; }
  const std::vector<Vehicle>& vehicles() const { return vehicles_; }
  const std::vector<VehicleTrack>& tracks() const { return tracks_; }
  const std::vector<LaneChangeEvent>& lane_changes() const { return lane_changes_; }
  const std::vector<StepSnapshot>& snapshots() const { return snapshots_; }
  int waiting_at_entry() const;  // arrivals not yet inserted (queue before the road start)

  // World motion and lateral offset of a vehicle now.
  WorldMotion world_motion_of(const Vehicle& v) const;
  double lateral_offset_m(const Vehicle& v) const;
  bool inside_conflict_area(const Vehicle& v) const;

 private:
  struct LaneEntry {
    double s_m;
    int vehicle;
  };
  struct Neighbour {
    int vehicle = -1;  // -1: none
    double gap_m = 0.0;
  };

  void build_roads();
  void fill_initial(Rng& rng);
  Vehicle make_vehicle(int vehicle_class, Rng& rng);
  void add_vehicle(Vehicle v);
  void rebuild_lane_lists();
  void insert_into_lane(int road, int lane, int vehicle);
  Neighbour leader_in_lane(int road, int lane, double s_m, int self) const;
  Neighbour follower_in_lane(int road, int lane, double s_m, int self) const;
  double gap_between_m(const Vehicle& follower, const Vehicle& leader, double distance_m) const;
  double idm_towards(const Vehicle& follower, const Neighbour& leader) const;
  double acceleration_of(int index) const;
  void decide_lane_changes();
  void update_crossings();
  void inflow(Rng& rng);
  void integrate();
  void sample_tracks(bool force_all);
  void append_sample(std::size_t i);
  void snapshot();
  double lane_count(int road) const { return roads_[road].lane_count; }

  TrafficConfig config_;
  std::vector<Road> roads_;
  std::vector<Vehicle> vehicles_;
  std::vector<std::vector<std::vector<LaneEntry>>> lanes_;  // [road][lane] sorted by s
  std::vector<std::vector<double>> next_arrival_t_s_;        // [road][lane]
  std::vector<std::vector<int>> waiting_;                    // [road][lane] arrivals not yet on the road
  std::vector<int> class_counters_;
  std::vector<double> accel_now_mps2_;
  std::vector<VehicleTrack> tracks_;
  std::vector<LaneChangeEvent> lane_changes_;
  std::vector<StepSnapshot> snapshots_;
  long long step_index_ = 0;
  long long sample_every_steps_ = 1;
  double conflict_s_lo_m_ = 0.0;  // intersection: the conflict area along each arm
  double conflict_s_hi_m_ = 0.0;
};

// Group of an intersection road: 0 for the x road (arms 0, 1), 1 for the y road (arms 2, 3).
inline int crossing_group(int road) { return road / 2; }

}  // namespace rcsim::traffic
