// connection.cpp - one client's ARCOS connection: SYNC handshake, OPEN/CLOSE/PULSE,
// commands to the robot.
#include "connection.hpp"

#include <algorithm>
#include <cstring>
#include <string>

namespace hlsim {

namespace {

void copy_id(char *dst, const std::string &s)
{
    std::size_t n = std::min<std::size_t>(s.size(), HL_ARCOS_ID_MAX - 1);
    std::memcpy(dst, s.data(), n);
    dst[n] = '\0';
}

// Appends the framed one-byte packet @p b (the SYNC echoes).
void append_echo(uint8_t b, std::vector<uint8_t> *out)
{
    uint8_t buf[8];
    std::size_t len = 0;
    if (hl_arcos_frame(buf, sizeof buf, &b, 1, &len) == HL_OK)
        out->insert(out->end(), buf, buf + len);
}

}  // namespace

Connection::Connection(SimRobot &robot, Log &log, bool lockstep)
    : robot_(robot), log_(log), lockstep_(lockstep)
{
    copy_id(id_.name, "houghloc-sim");
    copy_id(id_.cls, "Pioneer");
    copy_id(id_.subclass, robot.profile().name);
    hl_arcos_parser_init(&parser_);
}

void Connection::begin()
{
    hl_arcos_parser_discard(&parser_);
    // The parser's counters run on across connections; remember where this one starts.
    seen_checksums_ = parser_.bad_checksums;
    seen_lengths_ = parser_.bad_lengths;
    seen_garbage_ = parser_.garbage_bytes;
    state_ = State::Sync0;
    granted_ = false;
    held_.clear();
}

void Connection::end()
{
    granted_ = false;
    held_.clear();
    if (state_ == State::Idle)
        return;
    robot_.connection_end();
    state_ = State::Idle;
}

void Connection::bad(const std::string &kind, const char *what, unsigned number)
{
    bad_++;
    log_.once(kind, "ignored from the client: %s (command %u); such packets are counted, "
              "logged once", what, number);
}

// Turns the parser's rejected candidates and skipped bytes into counts and log lines.
void Connection::count_parser()
{
    uint64_t cs = parser_.bad_checksums - seen_checksums_;
    uint64_t len = parser_.bad_lengths - seen_lengths_;
    uint64_t junk = parser_.garbage_bytes - seen_garbage_;
    if (cs > 0)
        log_.once("checksum", "a client packet with a bad checksum: dropped (counted, "
                  "logged once)");
    if (len > 0)
        log_.once("count", "a client packet with a byte count outside 3..249: dropped "
                  "(counted, logged once)");
    if (junk > 0)
        log_.once("garbage", "bytes from the client outside any packet: skipped (counted, "
                  "logged once)");
    bad_ += cs + len;
    garbage_ += junk;
    seen_checksums_ = parser_.bad_checksums;
    seen_lengths_ = parser_.bad_lengths;
    seen_garbage_ = parser_.garbage_bytes;
}

void Connection::feed(const uint8_t *in, std::size_t n, std::vector<uint8_t> *out)
{
    if (state_ == State::Idle || state_ == State::Closed)
        return;
    if (!wants_input()) {
        // Lockstep, a period granted and not run: these bytes come after the grant.
        held_.insert(held_.end(), in, in + n);
        return;
    }
    process(in, n, out);
}

void Connection::period_done(std::vector<uint8_t> *out)
{
    if (!granted_)
        return;
    granted_ = false;
    std::vector<uint8_t> bytes;
    bytes.swap(held_);
    // Even with nothing held the parser may hold a whole packet of its own (after a
    // resynchronization): the empty call hands it out.
    if (state_ != State::Idle && state_ != State::Closed)
        process(bytes.data(), bytes.size(), out);
}

// Parses and carries out packets in order; in lockstep it stops after a packet that
// grants a period, holding the bytes after it back for period_done().
void Connection::process(const uint8_t *in, std::size_t n, std::vector<uint8_t> *out)
{
    std::size_t off = 0, used = 0;
    hl_arcos_packet_t pkt;
    while (hl_arcos_parse(&parser_, in + off, n - off, &used, &pkt) == HL_OK) {
        off += used;
        packet(pkt, out);
        if (state_ == State::Closed)
            break;   // nothing after CLOSE counts
        if (granted_) {
            held_.assign(in + off, in + n);
            break;
        }
    }
    count_parser();
}

// The handshake: SYNC0, SYNC1, SYNC2 in order, each answered; a SYNC0 at any point
// starts it over (a client retrying). @return false for a packet that is not the next
// step.
bool Connection::handshake(const hl_arcos_packet_t &pkt, std::vector<uint8_t> *out)
{
    if (pkt.len != 1 || pkt.data[0] > HL_ARCOS_SYNC2)
        return false;
    uint8_t sync = pkt.data[0];
    if (sync == HL_ARCOS_SYNC0) {
        append_echo(sync, out);
        state_ = State::Sync1;
        return true;
    }
    if (sync == HL_ARCOS_SYNC1 && state_ == State::Sync1) {
        append_echo(sync, out);
        state_ = State::Sync2;
        return true;
    }
    if (sync == HL_ARCOS_SYNC2 && state_ == State::Sync2) {
        uint8_t buf[HL_ARCOS_PACKET_MAX];
        std::size_t len = 0;
        if (hl_arcos_encode_sync2(buf, sizeof buf, &id_, &len) == HL_OK)
            out->insert(out->end(), buf, buf + len);
        state_ = State::Ready;
        log_.line("client synchronized (robot houghloc-sim, Pioneer, %s)", id_.subclass);
        return true;
    }
    return false;
}

void Connection::packet(const hl_arcos_packet_t &pkt, std::vector<uint8_t> *out)
{
    robot_.heard();
    if (state_ == State::Sync0 || state_ == State::Sync1 || state_ == State::Sync2) {
        if (!handshake(pkt, out))
            bad("before-sync", "a packet out of the SYNC0, SYNC1, SYNC2 order",
                pkt.len > 0 ? pkt.data[0] : 0u);
        return;
    }
    hl_arcos_cmd_t cmd;
    hl_status_t st = hl_arcos_decode_cmd(&pkt, &cmd);
    if (st == HL_ERR_PARSE) {
        bad("malformed", "a malformed command", cmd.number);
        return;
    }
    if (st != HL_OK) {
        bad("unsupported-" + std::to_string(cmd.number),
            "a command outside the supported subset or its argument range", cmd.number);
        return;
    }
    take(cmd);
}

void Connection::take(const hl_arcos_cmd_t &cmd)
{
    switch (cmd.number) {
    case HL_ARCOS_PULSE:
        break;
    case HL_ARCOS_OPEN:
        if (state_ != State::Open) {
            log_.line("OPEN: the SIP stream starts");
            granted_ = lockstep_;   // lockstep: the first SIP period
        }
        state_ = State::Open;
        break;
    case HL_ARCOS_STEP:
        if (!lockstep_)
            return;   // the lockstep clock's, and this clock is live: taken, ignored
        if (state_ != State::Open) {
            bad("step-before-open", "a STEP before OPEN, which grants nothing", cmd.number);
            return;
        }
        granted_ = true;
        steps_++;
        break;
    case HL_ARCOS_CLOSE:
        log_.line("CLOSE: the connection ends; the robot stops");
        robot_.connection_end();
        state_ = State::Closed;
        break;
    default: {
        // a STOP reaching a robot the client cannot hear: what a client that noticed the
        // silence should send (the speeds are the robot's as the STOP came)
        const double v = robot_.base().velocity(), w = robot_.base().rot_velocity();
        if (!robot_.command(cmd)) {
            bad_++;
            return;
        }
        if (muted_ && cmd.number == HL_ARCOS_STOP) {
            muted_stops_++;
            log_.line("fault: muted: the client sent STOP (%llu so far) at %.0f mm/s and "
                      "%.1f deg/s", static_cast<unsigned long long>(muted_stops_), v,
                      rad2deg(w));
        }
        break;
    }
    }
    commands_++;
}

}  // namespace hlsim
