// logwriter.cpp - LCM event log output of the simulator.
#include "logwriter.hpp"

#include <cmath>
#include <lcm/eventlog.h>

#include "houghloc/fixed.h"
#include "houghloc_odometry_t.h"
#include "houghloc_pose_t.h"
#include "houghloc_scan_t.h"

namespace hlsim {

namespace {

int32_t mm(double v)
{
    return static_cast<int32_t>(std::lround(v));
}

int16_t bam(double rad)
{
    return static_cast<int16_t>(hl_bam_from_rad(rad));
}

houghloc_odometry_t odo_msg(int64_t utime, const Pose &p, double velocity, bool stopped)
{
    houghloc_odometry_t m{};
    m.utime = utime;
    m.x_mm = mm(p.x);
    m.y_mm = mm(p.y);
    m.heading_bam = bam(p.theta);
    m.velocity_mm_s = static_cast<int16_t>(std::lround(velocity));
    m.stopped = stopped ? 1 : 0;
    return m;
}

}  // namespace

LogWriter::~LogWriter()
{
    close();
}

bool LogWriter::open(const std::string &path, std::string *err)
{
    close();
    log_ = lcm_eventlog_create(path.c_str(), "w");
    if (!log_) {
        *err = path + ": cannot create log";
        return false;
    }
    eventnum_ = 0;
    ok_ = true;
    stats_ = LogStats();
    return true;
}

bool LogWriter::close()
{
    if (log_) {
        lcm_eventlog_destroy(log_);
        log_ = nullptr;
    }
    return ok_;
}

void LogWriter::write(const std::string &channel, int64_t utime, const std::vector<uint8_t> &data)
{
    if (!log_) {
        ok_ = false;
        return;
    }
    // Event timestamps never go backwards, as lcm-logger's would not.
    if (utime < last_utime_)
        utime = last_utime_;
    last_utime_ = utime;
    lcm_eventlog_event_t ev{};
    ev.eventnum = eventnum_++;
    ev.timestamp = utime;
    ev.channellen = static_cast<int32_t>(channel.size());
    ev.datalen = static_cast<int32_t>(data.size());
    ev.channel = const_cast<char *>(channel.c_str());
    ev.data = const_cast<uint8_t *>(data.data());
    if (lcm_eventlog_write_event(log_, &ev) != 0)
        ok_ = false;
}

void LogWriter::odometry(const std::vector<OdoSample> &samples, const std::string &channel)
{
    for (const OdoSample &s : samples) {
        houghloc_odometry_t m = odo_msg(s.utime, s.odom, s.velocity_mm_s, s.stopped);
        std::vector<uint8_t> buf(static_cast<std::size_t>(houghloc_odometry_t_encoded_size(&m)));
        if (houghloc_odometry_t_encode(buf.data(), 0, static_cast<int>(buf.size()), &m) < 0)
            ok_ = false;
        write(channel, s.utime, buf);
        stats_.odometry++;
    }
}

void LogWriter::sounding(const Sounding &s, int32_t seq, const hl_calib_t &calib,
                         const std::string &channel)
{
    std::size_t n = s.readings.size();
    std::vector<int8_t> transducer(n), valid(n);
    std::vector<int16_t> bearing(n);
    std::vector<int32_t> range(n);
    for (std::size_t i = 0; i < n; i++) {
        const RingReading &r = s.readings[i];
        transducer[i] = static_cast<int8_t>(r.transducer);
        bearing[i] = static_cast<int16_t>(r.bearing_bam);
        bool ok = hl_calib_apply(&calib, r.sonar.raw, &range[i]);
        valid[i] = ok ? 1 : 0;
        stats_.readings++;
        stats_.valid += ok ? 1 : 0;
        stats_.cable += r.sonar.kind == Echo::Cable ? 1 : 0;
        stats_.sentinel += r.sonar.raw >= calib.sentinel_raw ? 1 : 0;
        stats_.multipath += r.sonar.kind == Echo::Multipath ? 1 : 0;
    }
    houghloc_scan_t m{};
    m.utime = s.utime;
    m.seq = seq;
    m.odometry = odo_msg(s.utime, s.odom, 0.0, true);
    m.nreadings = static_cast<int16_t>(n);
    m.transducer = transducer.data();
    m.bearing_bam = bearing.data();
    m.range_mm = range.data();
    m.valid = valid.data();
    std::vector<uint8_t> buf(static_cast<std::size_t>(houghloc_scan_t_encoded_size(&m)));
    if (houghloc_scan_t_encode(buf.data(), 0, static_cast<int>(buf.size()), &m) < 0)
        ok_ = false;
    write(channel, s.utime, buf);
    stats_.scans++;

    houghloc_pose_t g{};
    g.utime = s.utime;
    g.scan_seq = seq;
    g.x_mm = mm(s.truth.x);
    g.y_mm = mm(s.truth.y);
    g.heading_bam = bam(s.truth.theta);
    g.status = HOUGHLOC_POSE_T_ACCEPTED;
    std::vector<uint8_t> gbuf(static_cast<std::size_t>(houghloc_pose_t_encoded_size(&g)));
    if (houghloc_pose_t_encode(gbuf.data(), 0, static_cast<int>(gbuf.size()), &g) < 0)
        ok_ = false;
    write("GROUND_TRUTH", s.utime, gbuf);
}

}  // namespace hlsim
