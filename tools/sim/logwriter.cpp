// logwriter.cpp - LCM event log output of the simulator. Messages are encoded by the
// validating codecs of houghloc/bus.h, the same code the daemon publishes with.
#include "logwriter.hpp"

#include <cmath>
#include <memory>
#include <lcm/eventlog.h>

#include "houghloc/bus.h"
#include "houghloc/fixed.h"
#include "houghloc/slam.h"

namespace hlsim {

namespace {

int32_t mm(double v)
{
    return static_cast<int32_t>(std::lround(v));
}

hl_pose_t to_pose(const Pose &p)
{
    return hl_pose_t{ mm(p.x), mm(p.y), hl_bam_from_rad(p.theta) };
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
        hl_bus_odometry_t m{};
        m.utime = s.utime;
        m.pose = to_pose(s.odom);
        m.velocity_mm_s = static_cast<int16_t>(std::lround(s.velocity_mm_s));
        m.stopped = s.stopped;
        std::vector<uint8_t> buf(HL_BUS_ODOMETRY_BYTES);
        int len = hl_bus_encode_odometry(&m, buf.data(), buf.size());
        if (len < 0) {
            ok_ = false;
            continue;
        }
        buf.resize(static_cast<std::size_t>(len));
        write(channel, s.utime, buf);
        stats_.odometry++;
    }
}

// A SCAN message of n readings taken at utime from odometry pose odom, its readings still
// to fill; null (and the writer failed) when n is more than a scan holds. hl_bus_scan_t
// holds HL_SCAN_MAX_READINGS readings: too large for the stack.
std::unique_ptr<hl_bus_scan> LogWriter::scan_header(int64_t utime, int32_t seq, const Pose &odom,
                                                      std::size_t n)
{
    if (n > HL_SCAN_MAX_READINGS) {
        ok_ = false;
        return nullptr;
    }
    auto m = std::make_unique<hl_bus_scan_t>();
    m->utime = utime;
    m->seq = seq;
    m->odometry = to_pose(odom);
    m->scan.count = static_cast<uint32_t>(n);
    return m;
}

void LogWriter::sounding(const Sounding &s, int32_t seq, const hl_calib_t &calib,
                         const std::string &channel)
{
    std::size_t n = s.readings.size();
    auto m = scan_header(s.utime, seq, s.odom, n);
    if (!m)
        return;
    for (std::size_t i = 0; i < n; i++) {
        const RingReading &r = s.readings[i];
        hl_reading_t &out = m->scan.readings[i];
        out.transducer = static_cast<int8_t>(r.transducer);
        out.bearing = static_cast<hl_bam_t>(r.bearing_bam);
        bool ok = hl_calib_apply(&calib, r.sonar.raw, &out.range_mm);  // clamped to 0..32767
        out.valid = ok;
        stats_.readings++;
        stats_.valid += ok ? 1 : 0;
        stats_.cable += r.sonar.kind == Echo::Cable ? 1 : 0;
        stats_.sentinel += r.sonar.raw >= calib.sentinel_raw ? 1 : 0;
        stats_.multipath += r.sonar.kind == Echo::Multipath ? 1 : 0;
    }
    scan_message(m.get(), s.utime, channel);
    ground_truth(s.utime, seq, s.truth);
}

void LogWriter::laser(const LaserScan &s, int32_t seq, const LaserParams &p)
{
    std::size_t n = s.range_mm.size();
    auto m = scan_header(s.utime, seq, s.odom, n);
    if (!m)
        return;
    for (std::size_t i = 0; i < n; i++) {
        hl_reading_t &out = m->scan.readings[i];
        int32_t r = s.range_mm[i];
        out.transducer = -1;
        out.bearing = hl_bam_from_deg(laser_bearing_deg(p, static_cast<int>(i)));
        out.valid = r >= 0 && r <= HL_RANGE_MAX_MM;
        out.range_mm = out.valid ? r : 0;
        stats_.readings++;
        stats_.valid += out.valid ? 1 : 0;
        stats_.sentinel += out.valid ? 0 : 1;
    }
    scan_message(m.get(), s.utime, "SONAR");
    ground_truth(s.utime, seq, s.truth);
}

void LogWriter::scan_message(const void *scan, int64_t utime, const std::string &channel)
{
    std::vector<uint8_t> buf(HL_BUS_SCAN_MAX_BYTES);
    int len = hl_bus_encode_scan(static_cast<const hl_bus_scan_t *>(scan), buf.data(), buf.size());
    if (len < 0) {
        ok_ = false;
        return;
    }
    buf.resize(static_cast<std::size_t>(len));
    write(channel, utime, buf);
    stats_.scans++;
}

void LogWriter::ground_truth(int64_t utime, int32_t seq, const Pose &truth)
{
    hl_bus_pose_t g{};
    g.utime = utime;
    g.scan_seq = seq;
    g.pose = to_pose(truth);
    g.status = HL_BUS_POSE_ACCEPTED;
    std::vector<uint8_t> gbuf(HL_BUS_POSE_BYTES);
    int len = hl_bus_encode_pose(&g, gbuf.data(), gbuf.size());
    if (len < 0) {
        ok_ = false;
        return;
    }
    gbuf.resize(static_cast<std::size_t>(len));
    write(HL_CHANNEL_GROUND_TRUTH, utime, gbuf);
}

}  // namespace hlsim
