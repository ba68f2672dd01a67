// test_lockstep.cpp - houghloc-sim's lockstep clock (--lockstep): OPEN grants one SIP
// period, each STEP one more; no period runs without a grant, none without a client; the
// packets after a grant wait for its period; STEP on the live clock is taken and ignored.
// And the point of it: the same client bytes, in the same order relative to the STEPs,
// give the same SIP byte stream and the same true poses, however the bytes were cut into
// reads and however late the client and the server were (a scripted client in a thread of
// its own, over loopback TCP, with irregular delays on both sides).
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstring>
#include <thread>

#include "connection.hpp"
#include "server.hpp"

#include "rooms.hpp"

// cmocka last: its macros (fail, ...) clash with standard headers included after it.
#include "test_support.hpp"
#include "server_rig.hpp"

using namespace hlsim;

namespace {

using Bytes = std::vector<uint8_t>;

Bytes none(uint8_t n)
{
    uint8_t b[HL_ARCOS_PACKET_MAX];
    std::size_t len = 0;
    assert_int_equal(hl_arcos_encode_none(b, sizeof b, n, &len), HL_OK);
    return Bytes(b, b + len);
}

Bytes with_int(uint8_t n, int32_t arg)
{
    uint8_t b[HL_ARCOS_PACKET_MAX];
    std::size_t len = 0;
    assert_int_equal(hl_arcos_encode_int(b, sizeof b, n, arg, &len), HL_OK);
    return Bytes(b, b + len);
}

Bytes cat(std::initializer_list<Bytes> parts)
{
    Bytes all;
    for (const Bytes &p : parts)
        all.insert(all.end(), p.begin(), p.end());
    return all;
}

Bytes handshake()
{
    return cat({none(HL_ARCOS_SYNC0), none(HL_ARCOS_SYNC1), none(HL_ARCOS_SYNC2)});
}

SimConfig bonnie()
{
    SimConfig c;
    sim_profile("bonnie", &c.profile);
    return c;
}

// The robot and one connection, bytes in and out, no sockets.
struct Bench {
    World world = six_metre_room();
    std::vector<std::string> lines;
    Log log{[this](const std::string &s) { lines.push_back(s); }};
    SimConfig cfg = bonnie();
    SimRobot robot;
    Connection connection;
    Bytes out;
    explicit Bench(bool lockstep)
        : robot(world, cfg, Pose{}, log), connection(robot, log, lockstep)
    {
        connection.begin();
    }
    void feed(const Bytes &b) { connection.feed(b.data(), b.size(), &out); }
    // What the server does with a grant: the period, then the input held behind it.
    void period()
    {
        assert_true(connection.period_granted());
        robot.step();
        connection.period_done(&out);
    }
};

}  // namespace

// Grants, and the packets after a grant held back until its period has run, even when
// they all arrive in one read.
static void test_grants_and_order(void **state)
{
    (void)state;
    Bench b(true);
    b.feed(handshake());
    assert_false(b.connection.period_granted());
    assert_true(b.connection.wants_input());
    // A STEP before OPEN grants nothing (counted as bad, logged once).
    b.feed(none(HL_ARCOS_STEP));
    assert_false(b.connection.period_granted());
    assert_int_equal(b.connection.bad_commands(), 1);
    // OPEN, two commands, STEP, MOVE, STEP, PULSE: one read.
    b.feed(cat({none(HL_ARCOS_OPEN), with_int(HL_ARCOS_ENABLE, 1), with_int(HL_ARCOS_SETV, 300),
                none(HL_ARCOS_STEP), with_int(HL_ARCOS_MOVE, 500), none(HL_ARCOS_STEP),
                none(HL_ARCOS_PULSE)}));
    // OPEN granted the first period; everything after it waits for that period.
    assert_true(b.connection.streaming());
    assert_true(b.connection.period_granted());
    assert_false(b.connection.wants_input());
    assert_true(b.connection.held_bytes() > 0);
    assert_false(b.robot.motors_on());
    assert_int_equal(b.connection.commands(), 1);
    // Bytes that come meanwhile queue up behind them.
    b.feed(with_int(HL_ARCOS_MOVE, 100));
    assert_false(b.robot.motors_on());
    // Period 1 runs: ENABLE and SETV are taken, the first STEP grants period 2, the MOVE
    // waits for it.
    b.period();
    assert_int_equal(b.robot.utime(), SimRobot::kSipPeriodUs);
    assert_true(b.robot.motors_on());
    assert_near(b.robot.base().limits.vmax, 300.0, 0.0);
    assert_true(b.connection.period_granted());
    assert_false(b.robot.base().moving());
    assert_int_equal(b.connection.steps(), 1);
    // Period 2: the MOVE is taken after it, the second STEP grants period 3.
    b.period();
    assert_true(b.robot.base().moving());
    assert_near(b.robot.base().odom().x, 0.0, 0.0);
    assert_true(b.connection.period_granted());
    assert_int_equal(b.connection.steps(), 2);
    // Period 3: PULSE and MOVE 100 taken; no grant left, input wanted again.
    b.period();
    assert_false(b.connection.period_granted());
    assert_true(b.connection.wants_input());
    assert_int_equal(b.connection.held_bytes(), 0);
    assert_int_equal(b.connection.commands(), 1 + 2 + 2 + 1 + 1 + 1);   // OPEN .. MOVE 100
    assert_int_equal(b.connection.bad_commands(), 1);
    // A period_done() without a grant does nothing.
    b.connection.period_done(&b.out);
    assert_false(b.connection.period_granted());
    // A second OPEN grants nothing; a CLOSE held behind a grant ends the connection
    // when its turn comes.
    b.feed(cat({none(HL_ARCOS_OPEN), none(HL_ARCOS_STEP), none(HL_ARCOS_CLOSE)}));
    assert_true(b.connection.period_granted());
    assert_false(b.connection.closed());
    b.period();
    assert_true(b.connection.closed());
    assert_false(b.robot.motors_on());
    // The connection's end drops a grant and what it held.
    b.connection.begin();
    b.feed(cat({handshake(), none(HL_ARCOS_OPEN), with_int(HL_ARCOS_ENABLE, 1)}));
    assert_true(b.connection.period_granted());
    b.connection.end();
    assert_false(b.connection.period_granted());
    assert_int_equal(b.connection.held_bytes(), 0);
    assert_true(b.connection.wants_input());
}

// On the live clock STEP is taken and ignored: counted neither as a command nor as bad,
// never a grant; every packet is carried out on arrival. It feeds the watchdog.
static void test_step_on_live_clock(void **state)
{
    (void)state;
    Bench b(false);
    b.feed(cat({handshake(), none(HL_ARCOS_OPEN), with_int(HL_ARCOS_ENABLE, 1),
                none(HL_ARCOS_STEP), with_int(HL_ARCOS_VEL, 200), none(HL_ARCOS_STEP)}));
    assert_true(b.connection.streaming());
    assert_true(b.robot.motors_on());
    assert_true(b.robot.base().moving());
    assert_false(b.connection.period_granted());
    assert_true(b.connection.wants_input());
    assert_int_equal(b.connection.commands(), 3);   // OPEN, ENABLE, VEL
    assert_int_equal(b.connection.bad_commands(), 0);
    assert_int_equal(b.connection.steps(), 0);
    // 1.9 s of robot time with nothing but STEPs from the client: the watchdog (2 s)
    // does not stop the robot; 2 s of silence afterwards do.
    for (int k = 0; k < 30; k++) {
        b.robot.step();
        if (k % 19 == 18)
            b.feed(none(HL_ARCOS_STEP));
    }
    assert_true(b.robot.base().moving());
    for (int k = 0; k < 25; k++)
        b.robot.step();
    assert_false(b.robot.base().velocity() > 0.0);
}

namespace {

// A server on loopback, the robot in a world, and the server's side of the loop.
struct Rig : ServerRig {
    Rig(const World &w, const SimConfig &c, const Pose &start, const Faults &f = Faults{})
        : ServerRig(w, c, start, f, true, 7) {}
};

void send_all(int fd, const Bytes &b)
{
    assert_int_equal(send(fd, b.data(), b.size(), 0), static_cast<ssize_t>(b.size()));
}

// The client's side: the bytes received, and how many SIPs among them.
struct Received {
    hl_arcos_parser_t parser;
    Bytes bytes;
    std::size_t sips = 0;
    bool eof = false;
    Received() { hl_arcos_parser_init(&parser); }
    void drain(int fd)
    {
        uint8_t buf[4096];
        for (;;) {
            ssize_t r = recv(fd, buf, sizeof buf, MSG_DONTWAIT);
            if (r == 0)
                eof = true;
            if (r <= 0)
                return;
            bytes.insert(bytes.end(), buf, buf + r);
            std::size_t off = 0, used = 0;
            hl_arcos_packet_t p;
            while (hl_arcos_parse(&parser, buf + off, static_cast<std::size_t>(r) - off,
                                  &used, &p) == HL_OK) {
                off += used;
                sips += hl_arcos_is_sip(&p);
            }
        }
    }
};

}  // namespace

// No SIP period without a grant: none without a client, none before OPEN, one for OPEN,
// one per STEP, however often the server is asked to step.
static void test_no_sip_without_credit(void **state)
{
    (void)state;
    Rig r(six_metre_room(), bonnie(), Pose{});
    uint64_t seq = 0;
    for (int k = 0; k < 20; k++) {
        assert_false(r.server.may_step());
        assert_false(r.server.step(&seq));
    }
    assert_int_equal(r.robot.utime(), 0);   // no client: robot time stands
    int fd = r.connect_client();
    Received rx;
    send_all(fd, handshake());
    for (int k = 0; k < 100 && rx.bytes.empty(); k++) {
        r.serve(10);
        rx.drain(fd);
    }
    assert_true(r.server.connected());
    for (int k = 0; k < 20; k++) {
        r.serve(1);
        assert_false(r.server.step(&seq));   // synchronized, not open: still nothing
    }
    assert_int_equal(r.robot.utime(), 0);
    // OPEN grants one period.
    send_all(fd, cat({none(HL_ARCOS_OPEN), with_int(HL_ARCOS_ENABLE, 1)}));
    for (int k = 0; k < 200 && !r.server.may_step(); k++)
        r.serve(10);
    int ran = 0;
    for (int k = 0; k < 30; k++) {
        ran += r.server.step(&seq);
        r.serve(1);
    }
    assert_int_equal(ran, 1);
    assert_int_equal(r.server.counts().sips, 1);
    assert_int_equal(r.robot.utime(), SimRobot::kSipPeriodUs);
    assert_true(r.robot.motors_on());   // taken after that period, before the next
    // Three STEPs in one packet of bytes: exactly three more.
    send_all(fd, cat({none(HL_ARCOS_STEP), none(HL_ARCOS_STEP), none(HL_ARCOS_STEP)}));
    for (int k = 0; k < 400 && r.server.counts().sips < 4; k++) {
        if (!r.server.step(&seq))
            r.serve(5);
    }
    for (int k = 0; k < 30; k++) {
        r.serve(1);
        assert_false(r.server.step(&seq));
    }
    assert_int_equal(r.server.counts().sips, 4);
    assert_int_equal(r.robot.utime(), 4 * SimRobot::kSipPeriodUs);
    for (int k = 0; k < 100 && rx.sips < 4; k++) {
        r.serve(5);
        rx.drain(fd);
    }
    assert_int_equal(rx.sips, 4);
    // A STEP and a hang-up: the period granted runs, then the connection ends; without
    // a client robot time stands again.
    send_all(fd, none(HL_ARCOS_STEP));
    close(fd);
    for (int k = 0; k < 200 && r.server.connected(); k++) {
        r.server.step(&seq);
        r.serve(5);
    }
    assert_false(r.server.connected());
    assert_int_equal(r.robot.utime(), 5 * SimRobot::kSipPeriodUs);
    for (int k = 0; k < 20; k++)
        assert_false(r.server.step(&seq));
    assert_int_equal(r.robot.utime(), 5 * SimRobot::kSipPeriodUs);
}

// Injected faults do not stop the lockstep clock: a SIP sent with a wrong checksum, which
// the client drops and so never answers, grants the next period itself; garbage before a
// SIP never holds a sync byte, so it cannot swallow the SIP after it.
static void test_faults_keep_the_clock(void **state)
{
    (void)state;
    Faults f;
    f.corrupt_every = 2;   // SIP 2 and SIP 4 are corrupt
    f.garbage_every = 1;   // garbage before every SIP
    Rig r(six_metre_room(), bonnie(), Pose{}, f);
    int fd = r.connect_client();
    Received rx;
    send_all(fd, cat({handshake(), none(HL_ARCOS_OPEN)}));
    for (int k = 0; k < 200 && !r.server.may_step(); k++)
        r.serve(10);
    uint64_t seq = 0;
    auto run_all = [&r, &seq]() {   // every period granted, until none is
        for (int k = 0; k < 30; k++) {
            if (!r.server.step(&seq))
                r.serve(1);
        }
    };
    run_all();
    assert_int_equal(r.server.counts().sips, 1);   // OPEN's period: a good SIP, answered
    send_all(fd, none(HL_ARCOS_STEP));
    for (int k = 0; k < 200 && r.server.counts().sips < 2; k++) {
        if (!r.server.step(&seq))
            r.serve(5);
    }
    run_all();
    // The STEP's period sent SIP 2, corrupt: SIP 3 ran with no STEP, and then the clock
    // waits again.
    assert_int_equal(r.server.counts().sips, 3);
    assert_int_equal(r.server.counts().corrupt, 1);
    assert_false(r.server.may_step());
    for (int k = 0; k < 100 && rx.sips < 2; k++) {
        r.serve(5);
        rx.drain(fd);
    }
    assert_int_equal(rx.sips, 2);   // SIPs 1 and 3, each found behind its garbage
    assert_int_equal(r.server.counts().garbage, 3);
    close(fd);
}

namespace {

// A client's script: the handshake and OPEN, then one segment per period, each the
// commands to take after that period and the STEP for the next.
std::vector<Bytes> script(bool shifted)
{
    std::vector<Bytes> seg(48, none(HL_ARCOS_STEP));
    auto at = [&seg](std::size_t k, const Bytes &b) {
        seg[k].insert(seg[k].begin(), b.begin(), b.end());   // before the segment's STEP
    };
    at(0, cat({with_int(HL_ARCOS_ENABLE, 1), with_int(HL_ARCOS_SONAR, 1),
               with_int(HL_ARCOS_SETV, 350)}));
    at(shifted ? 4 : 3, with_int(HL_ARCOS_MOVE, 1200));
    at(9, none(HL_ARCOS_PULSE));
    at(20, with_int(HL_ARCOS_HEAD, 120));
    at(24, cat({with_int(HL_ARCOS_VEL, 250), with_int(HL_ARCOS_RVEL, -15)}));
    at(28, none(HL_ARCOS_STOP));   // still by 4 s: the teleport due at 2 s goes then
    at(36, with_int(HL_ARCOS_SONARCYCLE, 30));
    at(40, none(HL_ARCOS_SETO));
    at(41, with_int(HL_ARCOS_MOVE, -600));
    return seg;
}

enum class Pace {
    Reactive,   // each segment sent once the SIP before it has arrived, in pieces
    Eager,      // everything at once, in random pieces, never waiting for a SIP
};

struct Outcome {
    Bytes stream;                               // every byte the client received
    std::vector<std::array<double, 4>> truth;   // utime, true x, y, heading per SIP
    uint64_t sips = 0;
    bool client_ok = false;
};

// Sends @p b in random pieces (1 .. max_piece bytes) with random pauses (0 .. max_us).
bool send_pieces(int fd, const Bytes &b, Rng &rng, int64_t max_piece, int64_t max_us)
{
    std::size_t off = 0;
    while (off < b.size()) {
        std::size_t n = std::min<std::size_t>(b.size() - off,
                                              static_cast<std::size_t>(rng.uniform_int(1, max_piece)));
        if (send(fd, b.data() + off, n, 0) != static_cast<ssize_t>(n))
            return false;
        off += n;
        std::this_thread::sleep_for(std::chrono::microseconds(rng.uniform_int(0, max_us)));
    }
    return true;
}

// Waits until @p rx holds @p want SIPs (at most 20 s).
bool wait_sips(int fd, Received &rx, std::size_t want)
{
    for (int k = 0; k < 20000 && rx.sips < want; k++) {
        struct pollfd p = {fd, POLLIN, 0};
        poll(&p, 1, 1);
        rx.drain(fd);
    }
    return rx.sips >= want;
}

// One run of the lab with a scripted client: the client in a thread of its own, the
// server's loop here; @p seed draws both sides' delays and the client's pieces.
Outcome run_script(const std::vector<Bytes> &segs, Pace pace, uint64_t seed, int64_t server_us)
{
    SimConfig cfg = bonnie();
    cfg.seed = 3;
    cfg.teleport.every_s = 2.0;   // the kidnapped robot too: random jumps, from the seed
    Faults faults;
    faults.garbage_every = 7;     // and bytes of garbage in the stream, from the seed
    Rig r(World::lab(), cfg, Pose{5400, 1500, 0}, faults);
    Outcome o;
    const std::size_t want = segs.size() + 1;   // OPEN's period and one per STEP
    int fd = r.connect_client();
    std::atomic<bool> ok{false};
    std::thread client([&o, &ok, &segs, fd, pace, seed, want] {
        Rng rng(seed);
        Received rx;
        bool good = send_pieces(fd, cat({handshake(), none(HL_ARCOS_OPEN)}), rng, 4, 300);
        for (std::size_t k = 0; good && k < segs.size(); k++) {
            if (pace == Pace::Reactive) {
                good = wait_sips(fd, rx, k + 1);
                std::this_thread::sleep_for(std::chrono::microseconds(rng.uniform_int(0, 2000)));
                good = good && send_pieces(fd, segs[k], rng, 3, 400);
            } else {
                good = send_pieces(fd, segs[k], rng, 64, k % 5 == 0 ? 1500 : 0);
            }
        }
        good = good && wait_sips(fd, rx, want);
        o.stream = rx.bytes;
        close(fd);
        ok = good;
    });
    Rng delays(seed ^ 0x5eedULL);
    bool seen = false;
    auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (std::chrono::steady_clock::now() < until) {
        r.serve(1);
        if (r.server.connected())
            seen = true;
        else if (seen)
            break;   // the client is done and gone
        if (r.server.may_step()) {
            std::this_thread::sleep_for(std::chrono::microseconds(delays.uniform_int(0, server_us)));
            uint64_t seq = 0;
            if (r.server.step(&seq)) {
                const Pose &p = r.robot.base().truth();
                o.truth.push_back({static_cast<double>(r.robot.utime()), p.x, p.y, p.theta});
            }
        }
    }
    client.join();
    o.client_ok = ok;
    o.sips = r.server.counts().sips;
    assert_true(r.server.counts().teleports >= 1);
    assert_true(r.server.counts().garbage >= 1);
    return o;
}

}  // namespace

// Reproducible: the same bytes in the same order relative to the STEPs give the same SIP
// stream, byte for byte, and the same true poses, however the client and the server are
// paced; a command moved by one STEP gives another.
static void test_reproducible(void **state)
{
    (void)state;
    const std::vector<Bytes> segs = script(false);
    Outcome a = run_script(segs, Pace::Reactive, 11, 3000);
    Outcome b = run_script(segs, Pace::Eager, 12, 500);
    Outcome c = run_script(segs, Pace::Eager, 13, 4000);
    Outcome d = run_script(segs, Pace::Reactive, 14, 0);
    for (const Outcome *o : {&a, &b, &c, &d}) {
        assert_true(o->client_ok);
        assert_int_equal(o->sips, segs.size() + 1);
        assert_int_equal(o->truth.size(), segs.size() + 1);
        assert_true(o->stream.size() > 40 * 20);
    }
    for (const Outcome *o : {&b, &c, &d}) {
        assert_int_equal(o->stream.size(), a.stream.size());
        assert_memory_equal(o->stream.data(), a.stream.data(), a.stream.size());
        for (std::size_t k = 0; k < a.truth.size(); k++)
            for (int i = 0; i < 4; i++)
                assert_true(o->truth[k][i] == a.truth[k][i]);   // bit for bit
    }
    // The robot did move, turn and jump.
    assert_true(std::fabs(a.truth.back()[1] - a.truth.front()[1]) > 300.0 ||
                std::fabs(a.truth.back()[2] - a.truth.front()[2]) > 300.0);
    // The MOVE one STEP later: another stream.
    Outcome e = run_script(script(true), Pace::Eager, 11, 500);
    assert_true(e.client_ok);
    assert_true(e.stream.size() != a.stream.size() ||
                std::memcmp(e.stream.data(), a.stream.data(), a.stream.size()) != 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_grants_and_order),
        cmocka_unit_test(test_step_on_live_clock),
        cmocka_unit_test(test_no_sip_without_credit),
        cmocka_unit_test(test_faults_keep_the_clock),
        cmocka_unit_test(test_reproducible),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
