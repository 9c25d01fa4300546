#include "freeturn/post/post_program.hpp"

#include <filesystem>

#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"
#include "freeturn/io/output_set.hpp"

namespace freeturn {

PostProgram::PostProgram(const PostPlugin& plugin, const MachineDescription& machine,
                         const ProgramSettings& settings, const std::string& path)
    : plugin_(plugin),
      machine_(machine),
      settings_(settings),
      guard_(machine_),
      watch_(plugin.post().name) {
  dropped_ = path.empty();
  main_name_ = dropped_ ? settings_.name + ".nc" : path;
  folder_ = std::filesystem::path(path).parent_path().string();
  files_.push_back(dropped_ ? nullptr : std::make_unique<AtomicFile>(path));
  current_ = files_.front().get();
  guard_.select_file(0, std::filesystem::path(main_name_).filename().string());
  info_.program_name = settings_.name.c_str();
  info_.machine_name = machine_.name.c_str();
  info_.dialect_settings = machine_.dialect_settings.c_str();
  info_.layout.count = static_cast<int>(machine_.axes.size());
  for (std::size_t i = 0; i < machine_.axes.size() && i < 4; ++i) {
    info_.layout.letters[i] = axis_letter(machine_.axes[i].axis)[0];
    info_.layout.decimals[i] = machine_.axes[i].decimals;
  }
  info_.c_wrapped = machine_.c_wrapped ? 1 : 0;
  info_.interpolation = machine_.interpolation == Interpolation::kCubic ? 1 : 0;
  info_.spindle_rpm = settings_.spindle_rpm;
  info_.feed = settings_.feed;
  info_.feed_per_minute = machine_.feed_per_minute ? 1 : 0;
  info_.block_count = settings_.block_count;
  info_.top_z = settings_.top_z;
  info_.z_away = settings_.z_away;
  writer_ = {this, &PostProgram::write_bytes, &PostProgram::open_file, &PostProgram::select_main};
  {
    PluginWatch::Call call(watch_, "create");
    handle_ = plugin_.post().create(&info_, &writer_, error_, sizeof error_);
  }
  if (handle_ == nullptr) fail("create");
  // A constructor that throws runs no destructor: the plugin's state is released here.
  try {
    check_output("create");
    int status;
    {
      PluginWatch::Call call(watch_, "begin");
      status = plugin_.post().begin(handle_, error_, sizeof error_);
    }
    check_output("begin");
    if (status != 0) fail("begin");
  } catch (...) {
    PluginWatch::Call call(watch_, "destroy");
    plugin_.post().destroy(handle_);
    handle_ = nullptr;
    throw;
  }
}

PostProgram::~PostProgram() {
  if (handle_) {
    PluginWatch::Call call(watch_, "destroy");
    plugin_.post().destroy(handle_);
  }
}

void PostProgram::check_output(const char* stage) {
  const std::string who =
      "post-processor '" + std::string(plugin_.post().name) + "' (" + plugin_.path() + ")";
  // The size limit is the job's: the error names its key (the command line reports it at
  // the key's place in the job file).
  if (!refused_.empty())
    throw InputError("limits.max_file_mb", refused_ + " (" + who + ", " + stage + "); no NC file was written");
  if (!guard_.ok()) {
    const std::string what = std::string(stage) +
                             ": wrote what no machine may get: " + guard_.reason() +
                             "; no NC file was written";
    // Every record was inside the travel before the plugin saw it: a word past it is the
    // plugin's own move (an approach or a retract, from its settings and the clearance
    // base), reported at the bound it crosses in the machine file.
    const NcGuard::Crossed crossed = guard_.crossed();
    // A feed per minute beyond an axis' velocity is the plugin's own (an approach or a
    // retract feed, from its settings): reported at the dialect settings.
    if (crossed.velocity)
      throw InputError(machine_.place_of_setting_in(what),
                       who + " " + what + " (its feed comes from the dialect settings here)");
    for (const AxisSpec& a : machine_.axes)
      if (crossed.letter == axis_letter(a.axis)[0]) {
        const auto& places = machine_.travel_places[static_cast<int>(a.axis)];
        const SourceLocation& place = crossed.upper ? places.max : places.min;
        if (!place.file.empty())
          throw InputError(place, std::string("machine axis ") + crossed.letter +
                                      (crossed.upper ? " max: " : " min: ") + who + " " + what);
      }
    // What a program's start and end hold beside the plugin's own words (a header, a
    // footer) comes from the machine file's dialect settings: reported there.
    const std::string_view s(stage);
    if (s == "begin" || s == "end")
      throw InputError(machine_.place_of_setting_in(what),
                       who + " " + what + " (its " + (s == "begin" ? "header" : "footer") +
                           " comes from the dialect settings here)");
    // Otherwise the job's machine is the place to look: it chose this post-processor.
    throw InputError(who, what, "machine");
  }
}

void PostProgram::fail(const char* stage) const {
  const std::string what = error_[0] ? error_ : "failed without a message";
  const std::string who =
      "post-processor '" + std::string(plugin_.post().name) + "' (" + plugin_.path() + ")";
  // A refusal at creation is of the dialect settings: it is reported where the machine
  // file states the setting it names.
  if (std::string(stage) == "create")
    throw InputError(machine_.place_of_setting_in(what), who + " refuses its settings: " + what);
  // A refusal of the blocks (block times a dialect cannot write, say) follows from the job
  // meeting this machine: reported at the job's machine key.
  throw InputError(who, std::string(stage) + ": " + what, "machine");
}

void PostProgram::write(std::span<const AxisRecord> chunk) {
  blocks_.resize(chunk.size());
  for (std::size_t k = 0; k < chunk.size(); ++k) {
    const std::string refused =
        guard_.check_record(chunk[k], blocks_written_ + static_cast<long long>(k) + 1);
    if (!refused.empty())
      throw InputError("NC guard (machine '" + machine_.name + "')",
                       refused + "; no NC file was written", "machine");
    // The plugin approaches and retracts beyond top_z: a block past it would be cut into
    // by those moves.
    if ((chunk[k].z - settings_.top_z) * settings_.z_away > 0)
      throw InputError("NC guard (machine '" + machine_.name + "')",
                       "block " + std::to_string(blocks_written_ + static_cast<long long>(k) + 1) +
                           ": Z " + significant_text(chunk[k].z, 9) +
                           " rises past the clearance base " +
                           significant_text(settings_.top_z, 9) +
                           " the approach and retract are planned from; no NC file was written",
                       "machine");
    blocks_[k] = {chunk[k].x, chunk[k].z, chunk[k].c, chunk[k].b, chunk[k].time};
  }
  blocks_written_ += static_cast<long long>(chunk.size());
  int status;
  {
    PluginWatch::Call call(watch_, "blocks");
    status = plugin_.post().blocks(handle_, blocks_.data(), blocks_.size(), error_, sizeof error_);
  }
  check_output("blocks");
  if (status != 0) fail("blocks");
}

void PostProgram::finish(OutputSet& outputs) {
  int status;
  {
    PluginWatch::Call call(watch_, "end");
    status = plugin_.post().end(handle_, error_, sizeof error_);
  }
  guard_.end_files();
  check_output("end");
  if (status != 0) fail("end");
  for (std::size_t k = 0; k < files_.size(); ++k)
    if (files_[k])
      outputs.adopt(std::move(files_[k]),
                    k == 0 ? OutputSet::Role::kProgram : OutputSet::Role::kData);
  files_.clear();
  current_ = nullptr;
  open_ = false;
}

std::vector<std::string> PostProgram::finish() {
  OutputSet outputs;
  finish(outputs);
  return outputs.commit();
}

int PostProgram::write_bytes(void* context, const char* data, size_t size) {
  auto* self = static_cast<PostProgram*>(context);
  try {
    // Closed once the files are handed over: a plugin writing from destroy().
    if (!self->open_ || !self->refused_.empty() || !self->guard_.ok()) return 1;
    const std::string_view bytes(data, size);
    self->guard_.feed(bytes);
    if (!self->guard_.ok()) return 1;
    self->program_bytes_ += static_cast<long long>(size);
    if (self->settings_.max_file_bytes >= 0 && self->program_bytes_ > self->settings_.max_file_bytes) {
      self->refused_ =
          "the program (" + self->main_name_ + " and its " +
          std::to_string(self->files_.size() - 1) +
          " child files) would be larger than limits.max_file_mb = " +
          significant_text(static_cast<double>(self->settings_.max_file_bytes) / (1 << 20), 6) +
          " MB";
      return 1;
    }
    if (self->current_) self->current_->write(bytes);
    return 0;
  } catch (const std::exception&) {
    return 1;
  }
}

int PostProgram::open_file(void* context, const char* name) {
  auto* self = static_cast<PostProgram*>(context);
  const std::filesystem::path file(name);
  if (!self->open_) return 1;  // handed over: the program has ended
  if (file.empty() || file.has_parent_path() || file.is_absolute()) return 1;
  try {
    self->files_.push_back(
        self->dropped_
            ? nullptr
            : std::make_unique<AtomicFile>((std::filesystem::path(self->folder_) / file).string()));
    self->current_ = self->files_.back().get();
    self->guard_.select_file(self->files_.size() - 1, file.string());
    return 0;
  } catch (const std::exception&) {
    return 1;
  }
}

int PostProgram::select_main(void* context) {
  auto* self = static_cast<PostProgram*>(context);
  if (!self->open_) return 1;
  self->current_ = self->files_.front().get();
  self->guard_.select_file(0, "");
  return 0;
}

std::string find_machine_file(const std::string& name) {
  if (name.find('/') != std::string::npos ||
      (name.size() > 5 && name.compare(name.size() - 5, 5, ".yaml") == 0)) {
    if (!std::filesystem::exists(name)) throw InputError(name, "the machine file does not exist");
    return name;
  }
  std::string looked;
  for (const std::string& folder : machine_search_path()) {
    const std::filesystem::path p = std::filesystem::path(folder) / (name + ".yaml");
    if (std::filesystem::exists(p)) return p.lexically_normal().string();
    looked += "\n  " + std::filesystem::path(folder).lexically_normal().string();
  }
  throw InputError("machine '" + name + "'", "no " + name + ".yaml in" + looked +
                                                 "\n(set FREETURN_MACHINE_PATH, or give a path)");
}

}  // namespace freeturn
