// connection.hpp - one client's ARCOS connection with the simulated robot, pure: client bytes
// in, reply bytes out (no sockets).
//
// A connection starts at the SYNC handshake: SYNC0 and SYNC1 are echoed, SYNC2 is answered
// with the robot's name, class and subclass. After it, command numbers 0, 1 and 2 mean
// PULSE, OPEN and CLOSE; OPEN starts the SIP stream (the server asks streaming()), CLOSE
// ends the connection (the robot stops; the server hangs up). Every other command of the
// subset goes to the robot. Bytes are reassembled by arcos.h's parser, so packets may
// arrive cut anywhere. Malformed, unsupported and out-of-order packets are logged once
// per kind, counted and ignored; every well-framed packet feeds the robot's watchdog.
//
// The lockstep clock (houghloc-sim --lockstep): OPEN grants one SIP period and each STEP
// one more. The packets after a grant wait, unread, until the server has run the period
// granted (period_done()), so each command lands between the same two SIP periods however
// the bytes were cut into reads and however long the server took: a command sent after
// the k-th grant is carried out after the k-th period and before the (k+1)-th. Without
// lockstep, STEP is taken and ignored, and every packet is carried out on arrival.
#ifndef HLSIMROBOT_CONNECTION_HPP
#define HLSIMROBOT_CONNECTION_HPP

#include <cstdint>
#include <vector>

#include "houghloc/arcos.h"
#include "log.hpp"
#include "simrobot.hpp"

namespace hlsim {

class Connection {
public:
    enum class State {
        Idle,     // no client
        Sync0,    // waiting for SYNC0
        Sync1,
        Sync2,
        Ready,    // handshake done, waiting for OPEN
        Open,     // SIPs flow
        Closed,   // CLOSE received
    };

    /** @p robot and @p log must outlive the connection; @p lockstep: the lockstep
     *  clock (see the top of the file). */
    Connection(SimRobot &robot, Log &log, bool lockstep = false);

    /** A client connected: the handshake starts over with an empty parser. */
    void begin();
    /**
     * Takes @p n bytes from the client and appends any reply (SYNC echoes, the SYNC2
     * answer) to @p out. Does nothing unless a connection is under way.
     */
    void feed(const uint8_t *in, std::size_t n, std::vector<uint8_t> *out);
    /** The client is gone (or CLOSE came): the robot stops; the connection is Idle (a
     *  period granted and not run, and the input held behind it, are dropped). */
    void end();

    /** Lockstep: a SIP period is granted (by OPEN or a STEP) and has not run yet. */
    bool period_granted() const { return granted_; }
    /**
     * Lockstep: the server has run the period granted. Takes the grant, then carries out
     * the client input held behind it, up to and including the next grant; replies go to
     * @p out. Does nothing unless a period was granted.
     */
    void period_done(std::vector<uint8_t> *out);
    /** Lockstep: the SIP just sent can never be answered (the fault injector broke its
     *  checksum, so the client drops it): the next period is granted as the client's STEP
     *  would have granted it, and the clock goes on one grant at a time. */
    void grant_unanswerable() { granted_ = lockstep_ && state_ == State::Open; }
    /** Whether the connection takes client bytes now: always without lockstep; with it,
     *  only while no granted period waits to run (the server leaves the rest in the
     *  socket meanwhile). */
    bool wants_input() const { return !lockstep_ || (!granted_ && held_.empty()); }
    /** Client bytes received and waiting behind a granted period. */
    std::size_t held_bytes() const { return held_.size(); }
    bool lockstep() const { return lockstep_; }

    State state() const { return state_; }
    bool streaming() const { return state_ == State::Open; }
    bool closed() const { return state_ == State::Closed; }

    uint64_t commands() const { return commands_; }          // commands taken
    uint64_t bad_commands() const { return bad_; }           // malformed, unsupported, ...
    uint64_t garbage_bytes() const { return garbage_; }      // bytes outside any packet
    uint64_t steps() const { return steps_; }                // STEPs taken (lockstep)
    uint64_t muted_stops() const { return muted_stops_; }    // STOPs taken while muted

    /** --mute-after: the robot's SIPs no longer reach the client (the server keeps them
     *  back), for good; each STOP taken from now on is logged and counted. */
    void set_muted() { muted_ = true; }

private:
    void process(const uint8_t *in, std::size_t n, std::vector<uint8_t> *out);
    void packet(const hl_arcos_packet_t &pkt, std::vector<uint8_t> *out);
    bool handshake(const hl_arcos_packet_t &pkt, std::vector<uint8_t> *out);
    void take(const hl_arcos_cmd_t &cmd);
    void bad(const std::string &kind, const char *what, unsigned number);
    void count_parser();

    SimRobot &robot_;
    Log &log_;
    hl_arcos_robot_id_t id_{};
    hl_arcos_parser_t parser_{};
    State state_ = State::Idle;
    bool lockstep_ = false;
    bool granted_ = false;           // lockstep: a period granted, not yet run
    std::vector<uint8_t> held_;      // lockstep: client bytes behind the granted period
    uint64_t commands_ = 0, bad_ = 0, garbage_ = 0, steps_ = 0, muted_stops_ = 0;
    bool muted_ = false;
    uint64_t seen_checksums_ = 0, seen_lengths_ = 0, seen_garbage_ = 0;
};

}  // namespace hlsim
#endif
