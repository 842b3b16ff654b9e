#include "traffic/traffic_sim.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/angles.hpp"

namespace rcsim::traffic {
namespace {

// Minimum-jerk lateral profile of a lane change along the path coordinate x in [0, 1]:
// q(x) = 10x^3 - 15x^4 + 6x^5 (zero slope and curvature at both ends, so the path is C2).
double q_profile(double x) { return x * x * x * (10.0 - 15.0 * x + 6.0 * x * x); }
double q_slope(double x) { return 30.0 * x * x * (1.0 - x) * (1.0 - x); }
double q_curvature(double x) { return 60.0 * x - 180.0 * x * x + 120.0 * x * x * x; }

}  // namespace

TrafficSimulation::TrafficSimulation(const TrafficConfig& config, Rng& rng) : config_(config) {
  sample_every_steps_ = std::llround(config_.sample_interval_s / config_.step_s);
  class_counters_.assign(config_.classes.size(), 0);
  build_roads();
  fill_initial(rng);
  for (std::size_t r = 0; r < roads_.size(); ++r) {
    for (int l = 0; l < roads_[r].lane_count; ++l) {
      const double rate_per_s = *config_.inflow_vph / 3600.0 / roads_[r].lane_count;
      next_arrival_t_s_[r][l] =
          rate_per_s > 0.0 ? time_s() + rng.exponential(1.0 / rate_per_s) : std::numeric_limits<double>::infinity();
    }
  }
  rebuild_lane_lists();
  sample_tracks(false);
}

void TrafficSimulation::build_roads() {
  const double w = config_.lane_width_m;
  if (config_.layout == Layout::Intersection) {
    // Two crossing two-lane roads; each arm is one direction, driving on the right.
    const double arm_m = config_.length_m;
    const Vec2 origins[4] = {{-arm_m, -0.5 * w}, {arm_m, 0.5 * w}, {0.5 * w, -arm_m}, {-0.5 * w, arm_m}};
    const double headings_rad[4] = {0.0, kPi, 0.5 * kPi, -0.5 * kPi};
    for (int i = 0; i < 4; ++i) roads_.push_back({Centerline::straight(origins[i], headings_rad[i], 2.0 * arm_m), 1, w});
    // The conflict area is the square |x|, |y| <= w shared by both roads.
    conflict_s_lo_m_ = arm_m - w;
    conflict_s_hi_m_ = arm_m + w;
  } else if (config_.layout == Layout::Ring) {
    roads_.push_back({Centerline::circle(config_.length_m), config_.lanes, w});
  } else if (config_.curve_radius_m > 0.0) {
    roads_.push_back({Centerline::winding(config_.length_m, config_.curve_radius_m, config_.curve_wavelength_m),
                      config_.lanes, w});
  } else {
    roads_.push_back({Centerline::straight(Vec2::Zero(), 0.0, config_.length_m), config_.lanes, w});
  }
  lanes_.assign(roads_.size(), {});
  next_arrival_t_s_.assign(roads_.size(), {});
  waiting_.assign(roads_.size(), {});
  for (std::size_t r = 0; r < roads_.size(); ++r) {
    lanes_[r].assign(roads_[r].lane_count, {});
    next_arrival_t_s_[r].assign(roads_[r].lane_count, 0.0);
    waiting_[r].assign(roads_[r].lane_count, 0);
  }
}

Vehicle TrafficSimulation::make_vehicle(int vehicle_class, Rng& rng) {
  const VehicleClass& c = config_.classes[vehicle_class];
  Vehicle v;
  v.vehicle_class = vehicle_class;
  v.idm = c.idm;
  double z = rng.normal();
  while (std::abs(z) > 2.0) z = rng.normal();  // truncated at 2 sigma
  v.idm.desired_speed_mps = c.idm.desired_speed_mps + z * c.desired_speed_sigma_mps;
  v.length_m = c.length_m;
  v.width_m = c.width_m;
  v.id = c.name + std::to_string(++class_counters_[vehicle_class]);
  v.enter_t_s = time_s();
  return v;
}

void TrafficSimulation::add_vehicle(Vehicle v) {
  if (config_.layout == Layout::Intersection && v.crossing == CrossingState::None) v.crossing = CrossingState::Approaching;
  VehicleTrack track;
  track.id = v.id;
  track.model = config_.classes[v.vehicle_class].model;
  track.is_ego = v.is_ego;
  if (time_s() > 1e-9) track.present_from_s = time_s();
  vehicles_.push_back(std::move(v));
  tracks_.push_back(std::move(track));
  accel_now_mps2_.push_back(0.0);
}

void TrafficSimulation::fill_initial(Rng& rng) {
  const int ego_road = 0;
  const int ego_lane = (roads_[0].lane_count - 1) / 2;
  const double v_ego_mps = config_.classes.front().idm.desired_speed_mps;
  double ego_s_m = 200.0;
  if (config_.layout == Layout::Ring) ego_s_m = 0.0;
  if (config_.layout == Layout::Intersection) {
    ego_s_m = std::max(10.0, conflict_s_lo_m_ - config_.conflict_request_distance_m - v_ego_mps * config_.warmup_s);
  }
  const int truck_class = static_cast<int>(config_.classes.size()) - 1;
  for (std::size_t r = 0; r < roads_.size(); ++r) {
    const double road_m = roads_[r].line.length_m();
    for (int l = 0; l < roads_[r].lane_count; ++l) {
      const bool ego_here = static_cast<int>(r) == ego_road && l == ego_lane;
      std::vector<double> slots_m;
      if (config_.density_vpkm > 0.0) {
        const double spacing_m = 1000.0 / config_.density_vpkm;
        const double offset_m = rng.uniform(0.0, spacing_m);
        for (double s = offset_m + 10.0; s < road_m - 10.0; s += spacing_m) {
          // Intersection: no vehicle starts between its request point and the far side of the
          // conflict area (it could not stop for the rule any more).
          if (config_.layout == Layout::Intersection && s + 10.0 > conflict_s_lo_m_ - config_.conflict_request_distance_m &&
              s - 10.0 < conflict_s_hi_m_ + 5.0) {
            continue;
          }
          slots_m.push_back(s + rng.uniform(-0.15, 0.15) * spacing_m);
        }
      }
      std::size_t ego_slot = slots_m.size();
      if (ego_here) {
        double best_m = std::numeric_limits<double>::infinity();
        for (std::size_t k = 0; k < slots_m.size(); ++k) {
          if (std::abs(slots_m[k] - ego_s_m) < best_m) best_m = std::abs(slots_m[k] - ego_s_m), ego_slot = k;
        }
        if (ego_slot == slots_m.size() || best_m > 30.0) {
          slots_m.push_back(ego_s_m);
          std::sort(slots_m.begin(), slots_m.end());
          ego_slot = static_cast<std::size_t>(std::find(slots_m.begin(), slots_m.end(), ego_s_m) - slots_m.begin());
        }
      }
      for (std::size_t k = 0; k < slots_m.size(); ++k) {
        const bool is_ego = ego_here && k == ego_slot;
        const int cls = !is_ego && rng.uniform01() < config_.truck_share ? truck_class : 0;
        Vehicle v = make_vehicle(cls, rng);
        if (is_ego) {
          v.is_ego = true;
          v.id = "ego";
          --class_counters_[cls];
        }
        v.road = static_cast<int>(r);
        v.lane = l;
        v.s_m = slots_m[k];
        if (config_.layout == Layout::Intersection && v.s_m > conflict_s_hi_m_) v.crossing = CrossingState::Cleared;
        add_vehicle(std::move(v));
      }
    }
  }
  // Start each vehicle at the equilibrium speed for its gap (Treiber 2000: s_e(v) inverted).
  rebuild_lane_lists();
  for (std::size_t i = 0; i < vehicles_.size(); ++i) {
    Vehicle& v = vehicles_[i];
    const Neighbour leader = leader_in_lane(v.road, v.lane, v.s_m, static_cast<int>(i));
    v.speed_mps = leader.vehicle < 0 ? v.idm.desired_speed_mps
                                     : std::min(v.idm.desired_speed_mps, idm_equilibrium_speed_mps(v.idm, leader.gap_m));
  }
}

double TrafficSimulation::lateral_offset_m(const Vehicle& v) const {
  const Road& road = roads_[v.road];
  if (!v.changing()) return road.lane_offset_m(v.lane);
  const double from_m = road.lane_offset_m(v.from_lane);
  return from_m + (road.lane_offset_m(v.lane) - from_m) * q_profile(v.change_progress);
}

WorldMotion TrafficSimulation::world_motion_of(const Vehicle& v) const {
  const Road& road = roads_[v.road];
  double slope = 0.0;
  double slope_rate_1pm = 0.0;
  if (v.changing()) {
    const double delta_m = road.lane_offset_m(v.lane) - road.lane_offset_m(v.from_lane);
    slope = delta_m * q_slope(v.change_progress) / v.change_length_m;
    slope_rate_1pm = delta_m * q_curvature(v.change_progress) / (v.change_length_m * v.change_length_m);
  }
  return world_motion(road.line, v.s_m, lateral_offset_m(v), slope, slope_rate_1pm, v.speed_mps);
}

bool TrafficSimulation::inside_conflict_area(const Vehicle& v) const {
  if (config_.layout != Layout::Intersection) return false;
  return v.s_m + 0.5 * v.length_m > conflict_s_lo_m_ && v.s_m - 0.5 * v.length_m < conflict_s_hi_m_;
}

int TrafficSimulation::waiting_at_entry() const {
  int n = 0;
  for (const auto& road : waiting_) {
    for (const int w : road) n += w;
  }
  return n;
}

void TrafficSimulation::rebuild_lane_lists() {
  for (auto& road : lanes_) {
    for (auto& lane : road) lane.clear();
  }
  for (std::size_t i = 0; i < vehicles_.size(); ++i) {
    const Vehicle& v = vehicles_[i];
    if (!v.active) continue;
    lanes_[v.road][v.lane].push_back({v.s_m, static_cast<int>(i)});
    if (v.changing()) lanes_[v.road][v.from_lane].push_back({v.s_m, static_cast<int>(i)});
  }
  for (auto& road : lanes_) {
    for (auto& lane : road) {
      std::sort(lane.begin(), lane.end(), [](const LaneEntry& a, const LaneEntry& b) {
        return a.s_m < b.s_m || (a.s_m == b.s_m && a.vehicle < b.vehicle);
      });
    }
  }
}

void TrafficSimulation::insert_into_lane(int road, int lane, int vehicle) {
  auto& list = lanes_[road][lane];
  const LaneEntry entry{vehicles_[vehicle].s_m, vehicle};
  list.insert(std::upper_bound(list.begin(), list.end(), entry,
                               [](const LaneEntry& a, const LaneEntry& b) {
                                 return a.s_m < b.s_m || (a.s_m == b.s_m && a.vehicle < b.vehicle);
                               }),
              entry);
}

double TrafficSimulation::gap_between_m(const Vehicle& follower, const Vehicle& leader, double distance_m) const {
  return distance_m - 0.5 * (follower.length_m + leader.length_m);
}

TrafficSimulation::Neighbour TrafficSimulation::leader_in_lane(int road, int lane, double s_m, int self) const {
  const auto& list = lanes_[road][lane];
  const Vehicle& me = vehicles_[self];
  auto it = std::upper_bound(list.begin(), list.end(), s_m, [](double s, const LaneEntry& e) { return s < e.s_m; });
  for (; it != list.end(); ++it) {
    if (it->vehicle != self) return {it->vehicle, gap_between_m(me, vehicles_[it->vehicle], it->s_m - s_m)};
  }
  if (roads_[road].line.closed()) {
    for (const LaneEntry& e : list) {
      if (e.vehicle != self) return {e.vehicle, gap_between_m(me, vehicles_[e.vehicle], e.s_m + roads_[road].line.length_m() - s_m)};
    }
  }
  return {};
}

TrafficSimulation::Neighbour TrafficSimulation::follower_in_lane(int road, int lane, double s_m, int self) const {
  const auto& list = lanes_[road][lane];
  const Vehicle& me = vehicles_[self];
  auto it = std::upper_bound(list.begin(), list.end(), s_m, [](double s, const LaneEntry& e) { return s < e.s_m; });
  while (it != list.begin()) {
    --it;
    if (it->vehicle != self) return {it->vehicle, gap_between_m(vehicles_[it->vehicle], me, s_m - it->s_m)};
  }
  if (roads_[road].line.closed()) {
    for (auto r = list.rbegin(); r != list.rend(); ++r) {
      if (r->vehicle != self) {
        return {r->vehicle, gap_between_m(vehicles_[r->vehicle], me, s_m + roads_[road].line.length_m() - r->s_m)};
      }
    }
  }
  return {};
}

double TrafficSimulation::idm_towards(const Vehicle& follower, const Neighbour& leader) const {
  if (leader.vehicle < 0) {
    return std::max(-follower.idm.emergency_decel_mps2, idm_free_acceleration_mps2(follower.idm, follower.speed_mps));
  }
  // Treiber 2000 eq. (1) with the approach rate dv = v - v_leader.
  return idm_acceleration_mps2(follower.idm, follower.speed_mps, leader.gap_m,
                               follower.speed_mps - vehicles_[leader.vehicle].speed_mps);
}

double TrafficSimulation::acceleration_of(int index) const {
  const Vehicle& v = vehicles_[index];
  // While changing lanes the vehicle keeps a safe gap in both lanes it occupies.
  double a_mps2 = idm_towards(v, leader_in_lane(v.road, v.lane, v.s_m, index));
  if (v.changing()) a_mps2 = std::min(a_mps2, idm_towards(v, leader_in_lane(v.road, v.from_lane, v.s_m, index)));
  if (v.crossing == CrossingState::Requested) {
    // Without the right to enter, the stop line before the conflict area is a standing obstacle.
    const double stop_gap_m = conflict_s_lo_m_ - 1.0 - (v.s_m + 0.5 * v.length_m);
    a_mps2 = std::min(a_mps2, idm_acceleration_mps2(v.idm, v.speed_mps, stop_gap_m, v.speed_mps));
  }
  return a_mps2;
}

void TrafficSimulation::decide_lane_changes() {
  if (config_.layout == Layout::Intersection) return;
  const double t_s = time_s();
  for (std::size_t idx = 0; idx < vehicles_.size(); ++idx) {
    const int i = static_cast<int>(idx);
    Vehicle& v = vehicles_[idx];
    if (!v.active || v.changing() || t_s < v.next_change_allowed_s || v.speed_mps < 1.0) continue;
    if (roads_[v.road].lane_count < 2) continue;
    const Neighbour leader = leader_in_lane(v.road, v.lane, v.s_m, i);
    const Neighbour old_follower = follower_in_lane(v.road, v.lane, v.s_m, i);
    double best_advantage_mps2 = 0.0;
    std::optional<LaneChangeEvent> best;
    for (const int dir : {-1, +1}) {
      const int target = v.lane + dir;
      if (target < 0 || target >= roads_[v.road].lane_count) continue;
      const Neighbour new_leader = leader_in_lane(v.road, target, v.s_m, i);
      const Neighbour new_follower = follower_in_lane(v.road, target, v.s_m, i);
      LaneChangeAccelerations acc;
      acc.changer_now_mps2 = accel_now_mps2_[idx];
      acc.changer_after_mps2 = idm_towards(v, new_leader);
      if (new_follower.vehicle >= 0) {
        const Vehicle& n = vehicles_[new_follower.vehicle];
        acc.new_follower_now_mps2 = accel_now_mps2_[new_follower.vehicle];
        acc.new_follower_after_mps2 = idm_towards(n, Neighbour{i, new_follower.gap_m});  // n behind the changer
        // A gap that does not fit both boxes is never safe, whatever the speeds.
        if (new_follower.gap_m <= 0.0) continue;
      }
      if (new_leader.vehicle >= 0 && new_leader.gap_m <= 0.0) continue;
      if (old_follower.vehicle >= 0) {
        const Vehicle& o = vehicles_[old_follower.vehicle];
        acc.old_follower_now_mps2 = accel_now_mps2_[old_follower.vehicle];
        Neighbour o_leader = leader;  // the old follower's leader after the change
        if (leader.vehicle >= 0) o_leader.gap_m = leader.gap_m + old_follower.gap_m + v.length_m;
        acc.old_follower_after_mps2 = idm_towards(o, o_leader);
      }
      if (!mobil_is_safe(config_.mobil, acc)) continue;
      const auto direction = dir > 0 ? LaneChangeDirection::Left : LaneChangeDirection::Right;
      const double advantage_mps2 = mobil_advantage_mps2(config_.mobil, acc, direction);
      if (advantage_mps2 <= best_advantage_mps2) continue;
      best_advantage_mps2 = advantage_mps2;
      LaneChangeEvent e;
      e.t_s = t_s;
      e.vehicle = v.id;
      e.from_lane = v.lane;
      e.to_lane = target;
      e.new_follower_after_mps2 = acc.new_follower_after_mps2;
      e.changer_after_mps2 = acc.changer_after_mps2;
      e.advantage_mps2 = advantage_mps2;
      if (new_follower.vehicle >= 0) {
        const Vehicle& n = vehicles_[new_follower.vehicle];
        e.has_new_follower = true;
        e.new_follower_idm = n.idm;
        e.new_follower_speed_mps = n.speed_mps;
        e.new_follower_gap_m = new_follower.gap_m;
        e.new_follower_approach_mps = n.speed_mps - v.speed_mps;
      }
      best = e;
    }
    if (!best) continue;
    v.from_lane = v.lane;
    v.lane = best->to_lane;
    v.change_progress = 0.0;
    v.change_length_m = std::max(config_.min_lane_change_length_m, v.speed_mps * config_.lane_change_time_s);
    insert_into_lane(v.road, v.lane, i);  // later deciders in this step see it in both lanes
    lane_changes_.push_back(*best);
  }
}

void TrafficSimulation::update_crossings() {
  if (config_.layout != Layout::Intersection) return;
  const double t_s = time_s();
  std::vector<int> queue;
  int active_group = -1;
  for (std::size_t i = 0; i < vehicles_.size(); ++i) {
    Vehicle& v = vehicles_[i];
    if (!v.active) continue;
    if (v.crossing == CrossingState::Approaching &&
        v.s_m + 0.5 * v.length_m >= conflict_s_lo_m_ - config_.conflict_request_distance_m) {
      v.crossing = CrossingState::Requested;
      v.request_t_s = t_s;
    }
    if (v.crossing == CrossingState::Granted && v.s_m - 0.5 * v.length_m > conflict_s_hi_m_) v.crossing = CrossingState::Cleared;
    if (v.crossing == CrossingState::Granted) active_group = crossing_group(v.road);
    if (v.crossing == CrossingState::Requested) queue.push_back(static_cast<int>(i));
  }
  // Conflict-area rule, first come first served: a request is granted when no vehicle of the
  // crossing road holds the area and none of the crossing road asked earlier. Vehicles of one
  // road (both directions) share the area; crossing roads never do.
  std::stable_sort(queue.begin(), queue.end(),
                   [&](int a, int b) { return vehicles_[a].request_t_s < vehicles_[b].request_t_s; });
  bool waiting_earlier[2] = {false, false};
  for (const int i : queue) {
    Vehicle& v = vehicles_[i];
    const int g = crossing_group(v.road);
    if ((active_group < 0 || active_group == g) && !waiting_earlier[1 - g]) {
      v.crossing = CrossingState::Granted;
      active_group = g;
    } else {
      waiting_earlier[g] = true;
    }
  }
}

void TrafficSimulation::inflow(Rng& rng) {
  const double t_s = time_s();
  const int truck_class = static_cast<int>(config_.classes.size()) - 1;
  for (std::size_t r = 0; r < roads_.size(); ++r) {
    if (roads_[r].line.closed()) continue;
    for (int l = 0; l < roads_[r].lane_count; ++l) {
      // Poisson arrivals: exponential headways of mean lanes / inflow.
      const double rate_per_s = *config_.inflow_vph / 3600.0 / roads_[r].lane_count;
      while (next_arrival_t_s_[r][l] <= t_s) {
        ++waiting_[r][l];
        next_arrival_t_s_[r][l] += rng.exponential(1.0 / rate_per_s);
      }
      if (waiting_[r][l] == 0) continue;
      // The first waiting vehicle enters with its rear at s = 0 when the IDM lets it do so
      // without braking harder than b: at its desired speed or slower.
      Vehicle v = make_vehicle(rng.uniform01() < config_.truck_share ? truck_class : 0, rng);
      v.road = static_cast<int>(r);
      v.lane = l;
      v.s_m = 0.5 * v.length_m;
      const auto& list = lanes_[r][l];
      bool blocked = !list.empty() && list.front().s_m - 0.5 * vehicles_[list.front().vehicle].length_m < v.length_m + 1.0;
      double speed_mps = v.idm.desired_speed_mps;
      if (!blocked && !list.empty()) {
        const Vehicle& lead = vehicles_[list.front().vehicle];
        const double gap_m = gap_between_m(v, lead, list.front().s_m - v.s_m);
        speed_mps = std::min(speed_mps, lead.speed_mps + 2.0);
        while (speed_mps > 0.0 &&
               idm_acceleration_mps2(v.idm, speed_mps, gap_m, speed_mps - lead.speed_mps) < -v.idm.comfortable_decel_mps2) {
          speed_mps = speed_mps > 1.0 ? 0.9 * speed_mps - 0.1 : 0.0;
        }
        blocked = gap_m < v.idm.min_gap_m ||
                  idm_acceleration_mps2(v.idm, speed_mps, gap_m, speed_mps - lead.speed_mps) < -v.idm.comfortable_decel_mps2;
      }
      if (blocked) {
        --class_counters_[v.vehicle_class];  // drawn again when the entry is free
        continue;
      }
      v.speed_mps = speed_mps;
      --waiting_[r][l];
      add_vehicle(std::move(v));
      insert_into_lane(static_cast<int>(r), l, static_cast<int>(vehicles_.size()) - 1);
    }
  }
}

void TrafficSimulation::integrate() {
  const double dt_s = config_.step_s;
  for (std::size_t i = 0; i < vehicles_.size(); ++i) {
    Vehicle& v = vehicles_[i];
    if (!v.active) continue;
    const double a_mps2 = accel_now_mps2_[i];
    // Ballistic update (Treiber & Kanagaraj 2015): v += a dt, s += v dt + a dt^2 / 2, stopping
    // exactly at v = 0 when braking to a standstill within the step.
    double ds_m = 0.0;
    const double v_new_mps = v.speed_mps + a_mps2 * dt_s;
    if (v_new_mps < 0.0) {
      ds_m = -0.5 * v.speed_mps * v.speed_mps / a_mps2;
      v.speed_mps = 0.0;
    } else {
      ds_m = v.speed_mps * dt_s + 0.5 * a_mps2 * dt_s * dt_s;
      v.speed_mps = v_new_mps;
    }
    v.accel_mps2 = a_mps2;
    v.s_m += ds_m;
    if (roads_[v.road].line.closed() && v.s_m >= roads_[v.road].line.length_m()) v.s_m -= roads_[v.road].line.length_m();
    if (v.changing()) {
      v.change_progress += ds_m / v.change_length_m;
      if (v.change_progress >= 1.0) {
        v.from_lane = -1;
        v.change_progress = 0.0;
        v.next_change_allowed_s = time_s() + dt_s + 2.0;  // settle before the next decision
      }
    }
  }
}

void TrafficSimulation::append_sample(std::size_t i) {
  VehicleTrack& track = tracks_[i];
  const double t_s = time_s();
  if (!track.samples.empty() && std::abs(track.samples.back().t_s - t_s) < 1e-9) return;
  const WorldMotion m = world_motion_of(vehicles_[i]);
  TrajectorySample s;
  s.t_s = t_s;
  s.x_m = m.x_m;
  s.y_m = m.y_m;
  s.yaw_rad = m.yaw_rad;
  s.speed_mps = m.speed_mps;
  s.yaw_rate_radps = m.yaw_rate_radps;
  track.samples.push_back(s);
}

void TrafficSimulation::sample_tracks(bool force_all) {
  if (time_s() < -1e-9) return;
  const long long scene_step = step_index_ - std::llround(config_.warmup_s / config_.step_s);
  const bool on_grid = scene_step % sample_every_steps_ == 0;
  for (std::size_t i = 0; i < vehicles_.size(); ++i) {
    // A vehicle's first sample is taken when it enters (or at scene time 0).
    if (vehicles_[i].active && (on_grid || force_all || tracks_[i].samples.empty())) append_sample(i);
  }
}

void TrafficSimulation::snapshot() {
  StepSnapshot snap;
  snap.t_s = time_s();
  for (std::size_t i = 0; i < vehicles_.size(); ++i) {
    const Vehicle& v = vehicles_[i];
    if (!v.active) continue;
    snap.vehicles.push_back({static_cast<int>(i), world_motion_of(v), v.s_m, lateral_offset_m(v), v.speed_mps,
                             v.accel_mps2, inside_conflict_area(v)});
  }
  snapshots_.push_back(std::move(snap));
}

void TrafficSimulation::step(Rng& rng) {
  update_crossings();
  rebuild_lane_lists();
  for (std::size_t i = 0; i < vehicles_.size(); ++i) {
    if (vehicles_[i].active) accel_now_mps2_[i] = acceleration_of(static_cast<int>(i));
  }
  decide_lane_changes();
  for (std::size_t i = 0; i < vehicles_.size(); ++i) {
    if (vehicles_[i].active) accel_now_mps2_[i] = acceleration_of(static_cast<int>(i));
  }
  integrate();
  ++step_index_;
  // Vehicles whose rear has passed the end of an open road leave the scene.
  for (std::size_t i = 0; i < vehicles_.size(); ++i) {
    Vehicle& v = vehicles_[i];
    if (!v.active || roads_[v.road].line.closed() || v.s_m - 0.5 * v.length_m <= roads_[v.road].line.length_m()) continue;
    if (time_s() >= -1e-9 && !tracks_[i].samples.empty()) {
      append_sample(i);  // its last sample, where it leaves
      tracks_[i].present_until_s = time_s();
    }
    v.active = false;
    v.leave_t_s = time_s();
  }
  rebuild_lane_lists();
  inflow(rng);
  sample_tracks(false);
  if (config_.record_steps) snapshot();
}

void TrafficSimulation::run(Rng& rng) {
  const long long total_steps = std::llround(config_.warmup_s / config_.step_s) +
                                static_cast<long long>(std::ceil(config_.duration_s / config_.step_s - 1e-9));
  while (step_index_ < total_steps) step(rng);
  sample_tracks(true);
}

}  // namespace rcsim::traffic
