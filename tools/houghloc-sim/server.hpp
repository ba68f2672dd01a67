// server.hpp - houghloc-sim's TCP side: one client at a time, its ARCOS connection, the SIP
// stream, and the injected faults.
//
// Non-blocking sockets for the caller's poll() loop: pollfds() says what to wait for,
// handle() does what became ready, step() runs one SIP period of the robot and queues the
// SIP for the client. Output waits in a buffer while the socket is full; a client that
// stops reading altogether is dropped rather than let the buffer grow.
//
// With the lockstep clock (the connection's, connection.hpp) a period runs only when the
// client has granted one: may_step() says so, step() refuses otherwise, and robot time
// stands still without a client. After the period's SIP is queued, the client input held
// behind the grant is carried out; the socket is read only while the connection wants
// input, so unread packets wait in the socket, in order.
#ifndef HLSIMROBOT_SERVER_HPP
#define HLSIMROBOT_SERVER_HPP

#include <poll.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "log.hpp"
#include "rng.hpp"
#include "connection.hpp"
#include "simrobot.hpp"

namespace hlsim {

/** Faults to inject (for tests); a negative time or a 0 period means never. */
struct Faults {
    double drop_after_s = -1.0;   // close the client's connection at this robot time, once
    double drop_every_s = -1.0;   // close each client's connection this long after it came
    uint64_t garbage_every = 0;   // every Nth SIP is preceded by 1..64 random bytes
    uint64_t corrupt_every = 0;   // every Nth SIP has a wrong checksum
    double stall_after_s = -1.0;  // from this robot time on the wheels do not turn
    double mute_after_s = -1.0;   // from this robot time on no SIP goes out (commands are
                                  // still read and obeyed: a one-way link loss)
};

struct ServerCounts {
    uint64_t sips = 0;       // SIPs queued for a client
    uint64_t clients = 0;    // connections taken
    uint64_t refused = 0;    // connections refused while one was open
    uint64_t drops = 0;      // injected: connections dropped
    uint64_t garbage = 0;    // injected: garbage runs
    uint64_t corrupt = 0;    // injected: bad checksums
    uint64_t stalls = 0;     // injected: wheel stalls
    uint64_t teleports = 0;  // injected: kidnappings (the robot's, SimRobot::teleports())
    uint64_t mutes = 0;      // injected: the SIP stream silenced (--mute-after, once)
    uint64_t faults() const { return drops + garbage + corrupt + stalls + teleports + mutes; }
};

class Server {
public:
    /** A client that has this much output unread is dropped. */
    static constexpr std::size_t kMaxBacklog = 256 * 1024;

    /** @p robot, @p connection and @p log must outlive the server. */
    Server(SimRobot &robot, Connection &connection, Log &log, const Faults &faults,
           uint64_t seed);
    ~Server();
    Server(const Server &) = delete;
    Server &operator=(const Server &) = delete;

    /** Listens on IPv4 @p addr, TCP @p port (0: any free port). @return false with one
     *  line in @p err. */
    bool listen(const std::string &addr, int port, std::string *err);
    /** The port listened on. */
    uint16_t port() const { return port_; }

    /**
     * Writes every byte sent to the first client to @p path as well, in the order sent,
     * until that client's connection ends: a capture of one ARCOS connection, which
     * houghlocd replays with robot.link = file:PATH. @return false with one line in @p err.
     */
    bool capture(const std::string &path, std::string *err);

    /** Fills up to 2 pollfds (listening socket, client) and returns how many. */
    std::size_t pollfds(struct pollfd *pfd) const;
    /** Handles what poll() reported for the pollfds() entries. */
    void handle(const struct pollfd *pfd, std::size_t n);

    /** Whether step() would run a period now: always with the live clock; with the
     *  lockstep clock, while a client is connected and has granted one. */
    bool may_step() const
    {
        return !connection_.lockstep() || (client_ >= 0 && connection_.period_granted());
    }

    /**
     * One SIP period: the faults due at this robot time, the robot's step, and the SIP
     * queued for the client when the stream is open; with the lockstep clock, then the
     * client input held behind the grant. @return true with @p seq set to the SIP's
     * number (0, 1, ... over all clients) if one was queued. With the lockstep clock and
     * no period granted (or the client dropped by a fault due now) nothing happens:
     * false, robot time unchanged.
     */
    bool step(uint64_t *seq);
    /** Whether the last step() ran a period for a client whose SIP --mute-after kept
     *  back (its @p seq is set: the number the next SIP sent will have). */
    bool period_muted() const { return period_muted_; }

    /** Closes the client and the listening socket. */
    void shutdown();

    bool connected() const { return client_ >= 0; }
    const ServerCounts &counts() const { return counts_; }

private:
    void accept_client();
    void read_client(bool all);
    void after_input();
    void flush();
    void close_client(const char *why);
    void end_capture();
    bool queue_sip(const hl_arcos_sip_t &sip);

    SimRobot &robot_;
    Connection &connection_;
    Log &log_;
    Faults faults_;
    Rng rng_;          // garbage bytes only: the robot's stream stays seed-determined
    int listen_ = -1, client_ = -1;
    uint16_t port_ = 0;
    std::vector<uint8_t> out_;
    bool dropped_ = false, stalled_ = false, muted_ = false, period_muted_ = false;
    bool corrupted_ = false;         // the last SIP queued was sent with a wrong checksum
    int64_t accepted_utime_ = 0;    // robot time the client connected (--drop-every)
    FILE *capture_ = nullptr;       // --capture, while the first client is connected
    std::string capture_path_;
    ServerCounts counts_;
};

}  // namespace hlsim
#endif
