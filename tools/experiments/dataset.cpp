// dataset.cpp - LCM event log -> soundings with ground truth (see dataset.hpp).
#include "dataset.hpp"

#include <cstdio>
#include <cstring>

#include <sys/types.h>
#include <map>

#include <lcm/eventlog.h>

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
    EventLog f;
    f.log = lcm_eventlog_create(path.c_str(), "r");
    if (!f.log) {
        *err = path + ": cannot open: " + std::strerror(errno);
        return false;
    }
    std::map<int32_t, hl_pose_t> truth;
    long n = 0;
    off_t good_end = 0;     // where the last complete event ended
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
            if (ok)
                out->push_back(std::move(s));
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
        good_end = ftello(f.log->f);
    }
    // liblcm stops at the first event it cannot read whole and says nothing: anything
    // left after the last complete event is a truncated or corrupt log, not a short one.
    if (fseeko(f.log->f, 0, SEEK_END) != 0 || ftello(f.log->f) != good_end) {
        *err = path + ": truncated or corrupt after event " + std::to_string(n) + " (byte " +
               std::to_string(static_cast<long long>(good_end)) + ")";
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
