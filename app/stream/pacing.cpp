#include "stream/pacing.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rcsim::stream {

Pacer::Pacer(const Options& options)
    : speed_(options.speed), tolerance_(options.late_tolerance), paused_(options.start_paused) {
  if (!std::isfinite(speed_) || speed_ < 0.0) throw std::invalid_argument("speed must be finite and ≥ 0");
}

TimePoint Pacer::deadline(double t_s) const {
  const double offset_ns = (t_s - anchor_t_s_) / speed_ * 1e9;
  return anchor_wall_ + std::chrono::nanoseconds(static_cast<std::int64_t>(std::llround(offset_ns)));
}

Pacer::Decision Pacer::decide(TimePoint now, double t_s) {
  if (paused_) return {credits_ > 0 ? Action::send : Action::hold, now};
  if (max_speed()) return {Action::send, now};
  if (!anchored_) {
    anchored_ = true;
    anchor_wall_ = now;
    anchor_t_s_ = t_s;
    return {Action::send, now};
  }
  const TimePoint due = deadline(t_s);
  if (now >= due) return {Action::send, now};
  return {Action::wait, due};
}

Pacer::SendRecord Pacer::on_sent(TimePoint sent, double t_s) {
  SendRecord record;
  if (paused_) {
    if (credits_ > 0) --credits_;
    return record;
  }
  if (max_speed() || !anchored_) return record;
  record.paced = true;
  record.lateness = sent - deadline(t_s);
  record.late = record.lateness > tolerance_;
  return record;
}

void Pacer::pause() {
  paused_ = true;
  credits_ = 0;
  anchored_ = false;
}

void Pacer::resume() {
  paused_ = false;
  credits_ = 0;
  anchored_ = false;
}

void Pacer::step(std::uint32_t cycles) {
  if (paused_) credits_ = static_cast<std::uint32_t>(std::min<std::uint64_t>(std::uint64_t{credits_} + cycles, 0xFFFFFFFFu));
}

void LatenessStats::add(const Pacer::SendRecord& record) {
  if (!record.paced) return;
  lateness_us_.push_back(static_cast<float>(std::chrono::duration<double, std::micro>(record.lateness).count()));
  sorted_ = false;
  if (record.late) ++late_;
}

double LatenessStats::quantile_ms(double p) const {
  if (lateness_us_.empty()) return 0.0;
  if (!sorted_) {
    std::sort(lateness_us_.begin(), lateness_us_.end());
    sorted_ = true;
  }
  const double rank = std::ceil(std::clamp(p, 0.0, 1.0) * static_cast<double>(lateness_us_.size()));
  const std::size_t index = std::max<std::size_t>(1, static_cast<std::size_t>(rank)) - 1;
  return lateness_us_[index] / 1000.0;
}

double LatenessStats::max_ms() const { return quantile_ms(1.0); }

}  // namespace rcsim::stream
