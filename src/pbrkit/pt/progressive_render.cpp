#include "pbrkit/pt/progressive_render.h"

#include <chrono>
#include <exception>

namespace pbrkit {

namespace {

using Clock = std::chrono::steady_clock;

// Nearest-neighbour upscaling of the preview to the job's size.
Image upscale(const Image& small, int width, int height) {
  Image out(width, height, small.channels);
  for (int y = 0; y < height; ++y) {
    const int sy = std::min(small.height - 1, y * small.height / height);
    for (int x = 0; x < width; ++x) {
      const int sx = std::min(small.width - 1, x * small.width / width);
      const float* s = small.pixel(sx, sy);
      float* d = out.pixel(x, y);
      for (int c = 0; c < small.channels; ++c) d[c] = s[c];
    }
  }
  return out;
}

double mean_count(const Film& film) {
  double sum = 0.0;
  for (float c : film.count) sum += c;
  return film.count.empty() ? 0.0 : sum / double(film.count.size());
}

double mean_noise(const Film& film) {
  double sum = 0.0;
  for (std::size_t i = 0; i < film.pixel_count(); ++i) sum += film.pixel_noise(i);
  return film.pixel_count() ? sum / double(film.pixel_count()) : 0.0;
}

}  // namespace

ProgressiveRender::~ProgressiveRender() {
  stop();
}

void ProgressiveRender::stop() {
  stop_ = true;
  if (worker_.joinable()) worker_.join();
}

std::uint64_t ProgressiveRender::start(ProgressiveJob job) {
  stop();
  stop_ = false;
  std::uint64_t id = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    id = ++jobs_;
    error_.reset();
    latest_.reset();  // nothing of the new job yet
  }
  worker_ = std::thread([this, id, job = std::move(job)]() mutable {
    const auto t0 = Clock::now();
    const auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
    try {
      PathTracerSettings s = job.settings;
      s.stop = &stop_;
      s.resume = nullptr;
      if (job.preview && s.width >= 8 && s.height >= 8) {
        PathTracerSettings p = s;
        p.width = std::max(1, s.width / 4);
        p.height = std::max(1, s.height / 4);
        p.spp = 1;
        p.min_spp = 1;
        p.sample_begin = p.sample_end = 0;
        p.checkpoint = nullptr;
        const PathTracerResult r = render_path(*job.scene, job.env.get(), job.camera, p);
        if (stop_.load()) return;
        ProgressiveSnapshot snap;
        snap.color = upscale(r.color, s.width, s.height);
        snap.preview = true;
        snap.seconds = seconds();
        snap.job = id;
        publish(std::move(snap));
      }
      const auto snapshot_of = [&](const Film& film, bool complete) {
        ProgressiveSnapshot snap;
        snap.color = film.color();
        snap.albedo = film.albedo_image();
        snap.normal = film.normal_image();
        snap.depth = film.depth_image();
        snap.spp = mean_count(film);
        snap.noise = mean_noise(film);
        snap.seconds = seconds();
        snap.complete = complete;
        snap.job = id;
        return snap;
      };
      s.checkpoint = [&](const Film& film) {
        if (!stop_.load()) publish(snapshot_of(film, false));
      };
      PathTracerResult r = render_path(*job.scene, job.env.get(), job.camera, s);
      if (stop_.load() && !r.stats.complete) return;
      ProgressiveSnapshot last = snapshot_of(r.film, r.stats.complete);
      if (r.stats.complete) last.film = std::make_shared<const Film>(std::move(r.film));
      publish(std::move(last));
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = e.what();
    }
  });
  return id;
}

void ProgressiveRender::publish(ProgressiveSnapshot snapshot) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (snapshot.job != jobs_) return;  // a stopped job's last words
  snapshot.serial = ++serial_;
  latest_ = std::make_shared<const ProgressiveSnapshot>(std::move(snapshot));
}

std::optional<ProgressiveSnapshot> ProgressiveRender::latest(std::uint64_t seen) const {
  std::shared_ptr<const ProgressiveSnapshot> s;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    s = latest_;
  }
  if (!s || s->serial <= seen) return std::nullopt;
  return *s;
}

std::optional<std::string> ProgressiveRender::error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

}  // namespace pbrkit
