// dataset.cpp - LCM event log -> soundings with ground truth (see dataset.hpp).
#include "dataset.hpp"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>

#include <lcm/eventlog.h>

#include "houghloc/logcheck.h"

namespace hlexp {

namespace {

struct EventLog {
    lcm_eventlog_t *log = nullptr;
    ~EventLog() { if (log) lcm_eventlog_destroy(log); }
};

std::string where(const std::string &path, long eventnum)
{
    return path + ": event " + std::to_string(eventnum) + ": ";
}

}  // namespace

bool read_soundings(const std::string &path, Soundings *out, std::string *err)
{
    // liblcm trusts every length field (a huge one crashes it) and stops silently at the
    // first event it cannot read: walk the framing first, and report the bad byte.
    hl_log_info_t info;
    char check_why[HL_LOG_WHY_LEN];
    if (hl_log_check(path.c_str(), &info, check_why) != HL_OK) {
        *err = check_why;
        return false;
    }
    EventLog f;
    f.log = lcm_eventlog_create(path.c_str(), "r");
    if (!f.log) {
        *err = path + ": cannot open: " + std::strerror(errno);
        return false;
    }
    std::map<int32_t, hl_pose_t> truth;
    long n = 0;
    // The ground truth is matched by seq, so a repeated seq would score a scan against
    // another's pose: seqs must increase over all the scan channels, as houghlocd wants.
    const Sounding *last = nullptr;
    char why[HL_BUS_WHY_LEN];
    for (;;) {
        lcm_eventlog_event_t *ev = lcm_eventlog_read_next_event(f.log);
        if (!ev)
            break;
        n++;
        std::string channel(ev->channel, ev->channellen);
        const void *data = ev->data;
        size_t len = ev->datalen;
        bool ok = true;
        if (channel.rfind("SONAR", 0) == 0) {
            auto s = std::make_unique<Sounding>();
            s->channel = channel;
            ok = hl_bus_decode_scan(data, len, &s->msg, why) == HL_OK;
            if (ok && last && s->msg.seq <= last->msg.seq) {
                std::snprintf(why, sizeof why, "seq %ld after seq %ld: scan seqs must increase",
                              static_cast<long>(s->msg.seq), static_cast<long>(last->msg.seq));
                ok = false;
            }
            if (ok) {
                last = s.get();
                out->push_back(std::move(s));
            }
        } else if (channel == HL_CHANNEL_GROUND_TRUTH) {
            hl_bus_pose_t p;
            ok = hl_bus_decode_pose(data, len, &p, why) == HL_OK;
            if (ok)
                truth[p.scan_seq] = p.pose;
        }
        lcm_eventlog_free_event(ev);
        if (!ok) {
            *err = where(path, n) + channel + ": " + why;
            return false;
        }
    }
    // liblcm also stops at an allocation failure, and the file may have changed since
    // the check: every event the check counted must have been read.
    if (static_cast<uint64_t>(n) != info.events) {
        *err = path + ": read " + std::to_string(n) + " of " + std::to_string(info.events) +
               " events";
        return false;
    }
    if (out->empty()) {
        *err = path + ": no SONAR scans in the log";
        return false;
    }
    for (auto &s : *out) {
        auto it = truth.find(s->msg.seq);
        if (it == truth.end()) {
            *err = path + ": scan " + std::to_string(s->msg.seq) + " has no GROUND_TRUTH pose";
            return false;
        }
        s->truth = it->second;
        s->has_truth = true;
    }
    return true;
}

std::vector<const Sounding *> on_channel(const Soundings &all, const std::string &channel)
{
    std::vector<const Sounding *> v;
    for (const auto &s : all)
        if (s->channel == channel)
            v.push_back(s.get());
    return v;
}

}  // namespace hlexp
