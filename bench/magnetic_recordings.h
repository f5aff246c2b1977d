// The magnetic recordings the magnetic benches run on: the real ones read in place from
// ../shared/data/magnetic (Aalto invensense trials 1-9, Kok & Solin's walks) and walks made here
// through a synthetic field (a long loop; a corridor walked back and forth).
#pragma once

#include <lodestone/datasets/MagneticRecording.h>
#include <lodestone/datasets/MagneticRecordingImport.h>
#include <lodestone/slamapp/SlamRun.h>

#include <functional>
#include <string>
#include <vector>

struct Recording {
    std::string name;  ///< "<set> <walk>", e.g. "kok eight"
    std::function<lodestone::datasets::MagneticRecording()> read;
};

/** A long walk, the kind the Kok walks are too short to be: `laps` laps of a 40 m x 20 m
 * rectangle (the first revisit 120 m after the start) at 1.2 m/s, 10 Hz; every second lap
 * 0.3 m beside the first. */
lodestone::datasets::MagneticRecording syntheticLongWalk(int laps = 2);

/** A plain 30 m corridor walked back and forth, three times each way (no lap: every revisit
 * after the first is walked the other way or the same way as one before), each pass at its own
 * offset of up to 0.15 m across; 1.2 m/s, 10 Hz. */
lodestone::datasets::MagneticRecording syntheticCorridorWalk();

/** Aalto trials 1-9 and the Kok walks under `data` (when present), then the synthetic walks. */
std::vector<Recording> benchRecordings(const std::string& data);

/** `recording` imported with the drift model of `seed` as the rawlog `path` (and its ground
 * truth beside it); `driftScale` scales the model's heading bias and noise sigmas (0: the
 * odometry is the reference trajectory). */
lodestone::datasets::MagneticImportResult importSeed(const lodestone::datasets::MagneticRecording& recording,
                                               const std::string& path, int seed,
                                               double driftScale = 1.0);

/** One quiet run of lodestone-slam's code path on an imported rawlog, read from disk: `config`
 * is a config_ini/ name, or a path when it names a folder; started in the map `mapIn`
 * (localize) and writing the map `mapOut` when given. */
struct TimedRun {
    lodestone::slamapp::SlamRunOptions options;
    lodestone::slamapp::SlamRunResult result;
    double wallSeconds{0};
    std::string errors;  ///< what the run wrote to its error stream
    bool ok() const { return result.exitCode == 0 && result.ateRmse.has_value(); }
};
TimedRun runImported(const lodestone::datasets::MagneticImportResult& imported, const std::string& config,
                     const std::string& outDir, const std::string& mapIn = "",
                     const std::string& mapOut = "");
