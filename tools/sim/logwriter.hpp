// logwriter.hpp - writes simulated soundings, odometry and ground truth as an LCM
// event log (the format lcm-logger writes and lcm-logplayer replays).
#ifndef HLSIM_LOGWRITER_HPP
#define HLSIM_LOGWRITER_HPP

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "houghloc/calib.h"
#include "laser.hpp"
#include "robot.hpp"

struct hl_bus_scan;  // houghloc/bus.h

extern "C" {
typedef struct _lcm_eventlog_t lcm_eventlog_t;
}

namespace hlsim {

/** Counts of what went into a log, for the generator's report. */
struct LogStats {
    int scans = 0;
    int readings = 0;
    int valid = 0;       // valid after calibration and the garbage filter
    int cable = 0;       // low garbage raw
    int sentinel = 0;    // no-echo sentinel (dropout or nothing within range)
    int multipath = 0;
    int odometry = 0;    // ODOMETRY messages
};

class LogWriter {
public:
    LogWriter() = default;
    ~LogWriter();
    LogWriter(const LogWriter &) = delete;
    LogWriter &operator=(const LogWriter &) = delete;

    /** Creates (truncates) @p path. @return false with @p err on failure. */
    bool open(const std::string &path, std::string *err);
    /** Flushes and closes; @return false if any write failed. */
    bool close();

    /** ODOMETRY messages. */
    void odometry(const std::vector<OdoSample> &samples, const std::string &channel = "ODOMETRY");
    /**
     * A sounding on @p channel as houghloc_scan_t, readings calibrated with @p calib;
     * then its true pose on GROUND_TRUTH (status ACCEPTED, scan_seq = @p seq).
     */
    void sounding(const Sounding &s, int32_t seq, const hl_calib_t &calib,
                  const std::string &channel = "SONAR");

    /**
     * A laser scan on SONAR as houghloc_scan_t: one reading per beam at its bearing,
     * transducer -1, a lost return an invalid reading; then its true pose on
     * GROUND_TRUTH as for a sounding.
     */
    void laser(const LaserScan &s, int32_t seq, const LaserParams &p);

    const LogStats &stats() const { return stats_; }

private:
    std::unique_ptr<hl_bus_scan> scan_header(int64_t utime, int32_t seq, const Pose &odom,
                                             std::size_t n);
    void scan_message(const void *scan, int64_t utime, const std::string &channel);
    void ground_truth(int64_t utime, int32_t seq, const Pose &truth);
    void write(const std::string &channel, int64_t utime, const std::vector<uint8_t> &data);

    lcm_eventlog_t *log_ = nullptr;
    int64_t eventnum_ = 0;
    int64_t last_utime_ = 0;
    bool ok_ = true;
    LogStats stats_;
};

}  // namespace hlsim
#endif
