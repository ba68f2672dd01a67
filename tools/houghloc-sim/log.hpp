// log.hpp - houghloc-sim's event log: one line per event, "houghloc-sim: " in front.
//
// The robot model and the connection are pure (no I/O), so they report events through a
// Log whose sink the program points at stderr and the tests at a vector. Events that a
// misbehaving client could repeat at every packet are logged once per kind and counted
// by the caller.
#ifndef HLSIMROBOT_LOG_HPP
#define HLSIMROBOT_LOG_HPP

#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <set>
#include <string>

namespace hlsim {

class Log {
public:
    using Sink = std::function<void(const std::string &)>;

    /** A log writing to stderr. */
    Log() : sink_(stderr_sink) {}
    explicit Log(Sink sink) : sink_(std::move(sink)) {}

    /** Robot time, in microseconds, shown in front of each event (nullptr: none). */
    void set_clock(const int64_t *utime) { clock_ = utime; }

    /** One event. */
    void line(const char *fmt, ...) __attribute__((format(printf, 2, 3)))
    {
        va_list ap;
        va_start(ap, fmt);
        emit(fmt, ap);
        va_end(ap);
    }

    /** One event, logged only the first time its @p kind is seen. @return whether it
     *  was logged. */
    bool once(const std::string &kind, const char *fmt, ...) __attribute__((format(printf, 3, 4)))
    {
        if (!seen_.insert(kind).second)
            return false;
        va_list ap;
        va_start(ap, fmt);
        emit(fmt, ap);
        va_end(ap);
        return true;
    }

    static void stderr_sink(const std::string &s)
    {
        std::fprintf(stderr, "houghloc-sim: %s\n", s.c_str());
    }

private:
    void emit(const char *fmt, va_list ap)
    {
        char msg[512];
        std::vsnprintf(msg, sizeof msg, fmt, ap);
        if (!clock_) {
            sink_(msg);
            return;
        }
        char stamped[560];
        std::snprintf(stamped, sizeof stamped, "t=%.1f s: %s",
                      static_cast<double>(*clock_) / 1e6, msg);
        sink_(stamped);
    }

    Sink sink_;
    const int64_t *clock_ = nullptr;
    std::set<std::string> seen_;
};

}  // namespace hlsim
#endif
