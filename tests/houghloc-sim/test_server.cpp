// test_server.cpp - houghloc-sim end to end over a real loopback socket, server and client
// driven from one thread: handshake, a MOVE, one client at a time, injected garbage,
// corrupt checksums and a dropped connection, and the robot kept across clients; a
// connection dropped again and again (--drop-every), each living its full period; a
// muted robot (--mute-after) that sends nothing and still obeys a STOP.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include "options.hpp"
#include "server.hpp"

// cmocka last: its macros (fail, ...) clash with standard headers included after it.
#include "test_support.hpp"
#include "server_rig.hpp"

using namespace hlsim;

namespace {

// The room and the robot of every test here, on the live clock.
struct Rig : ServerRig {
    explicit Rig(const Faults &f) : ServerRig(make_world(), config(), Pose{}, f, false, 1) {}
    static World make_world()
    {
        World w;
        std::string err;
        w.parse("polygon -3000 -3000 3000 -3000 3000 3000 -3000 3000\n", "room", &err);
        return w;
    }
    static SimConfig config()
    {
        SimConfig c;
        sim_profile("bonnie", &c.profile);
        return c;
    }
    // Serves the sockets until @p done holds (at most 2 s).
    template <class F> void serve_until(F done)
    {
        for (int k = 0; k < 100 && !done(); k++)
            serve();
        assert_true(done());
    }
    int connect_client()
    {
        int fd = ServerRig::connect_client();
        serve();
        return fd;
    }
};

void send_cmd(int fd, uint8_t n, int32_t arg, bool has_arg)
{
    uint8_t b[HL_ARCOS_PACKET_MAX];
    std::size_t len = 0;
    hl_status_t st = has_arg ? hl_arcos_encode_int(b, sizeof b, n, arg, &len)
                             : hl_arcos_encode_none(b, sizeof b, n, &len);
    assert_int_equal(st, HL_OK);
    assert_int_equal(send(fd, b, len, 0), static_cast<ssize_t>(len));
}

// The client's side: everything readable now, parsed.
struct Reader {
    hl_arcos_parser_t parser;
    std::vector<hl_arcos_packet_t> packets;
    bool eof = false;
    Reader() { hl_arcos_parser_init(&parser); }
    void drain(int fd)
    {
        uint8_t buf[4096];
        for (;;) {
            ssize_t r = recv(fd, buf, sizeof buf, MSG_DONTWAIT);
            if (r == 0)
                eof = true;
            if (r <= 0)
                return;
            std::size_t off = 0, used = 0;
            hl_arcos_packet_t p;
            while (hl_arcos_parse(&parser, buf + off, static_cast<std::size_t>(r) - off,
                                  &used, &p) == HL_OK) {
                off += used;
                packets.push_back(p);
            }
        }
    }
};

// Connects, synchronizes and opens; returns the client's socket.
int open_connection(Rig &r, Reader &rd)
{
    int fd = r.connect_client();
    for (uint8_t k = 0; k < 3; k++) {
        send_cmd(fd, k, 0, false);
        for (int i = 0; i < 100 && rd.packets.size() < k + 1u; i++) {
            r.serve();
            rd.drain(fd);
        }
        assert_int_equal(rd.packets.size(), k + 1u);
        if (k < 2)
            assert_true(hl_arcos_is_sync_echo(&rd.packets[k], k));
    }
    hl_arcos_robot_id_t id;
    assert_int_equal(hl_arcos_decode_sync2(&rd.packets[2], &id), HL_OK);
    assert_string_equal(id.subclass, "bonnie");
    rd.packets.clear();
    send_cmd(fd, HL_ARCOS_OPEN, 0, false);
    send_cmd(fd, HL_ARCOS_ENABLE, 1, true);
    r.serve_until([&r] { return r.connection.streaming() && r.robot.motors_on(); });
    return fd;
}

// Runs @p steps SIP periods, serving the sockets and pulsing between them; returns the
// SIPs the client decoded.
std::vector<hl_arcos_sip_t> run(Rig &r, Reader &rd, int fd, int steps)
{
    std::vector<hl_arcos_sip_t> sips;
    for (int k = 0; k < steps; k++) {
        uint64_t seq = 0;
        r.server.step(&seq);
        if (k % 5 == 0 && r.server.connected())
            send_cmd(fd, HL_ARCOS_PULSE, 0, false);
        r.serve(1);
        rd.drain(fd);
    }
    r.serve(5);
    rd.drain(fd);
    for (const hl_arcos_packet_t &p : rd.packets) {
        hl_arcos_sip_t s;
        if (hl_arcos_is_sip(&p) && hl_arcos_decode_sip(&p, &s) == HL_OK)
            sips.push_back(s);
    }
    rd.packets.clear();
    return sips;
}

}  // namespace

static void test_move_over_tcp(void **state)
{
    (void)state;
    Rig r(Faults{});
    Reader rd;
    int fd = open_connection(r, rd);
    send_cmd(fd, HL_ARCOS_MOVE, 500, true);
    r.serve_until([&r] { return r.robot.base().moving(); });
    std::vector<hl_arcos_sip_t> sips = run(r, rd, fd, 40);
    assert_int_equal(sips.size(), 40);
    assert_int_equal(r.server.counts().sips, 40);
    assert_int_equal(sips.front().type, HL_ARCOS_SIP_MOVING);
    assert_int_equal(sips.back().type, HL_ARCOS_SIP_STOPPED);
    assert_int_equal(sips.back().x, 500);
    // A second client is turned away; the first keeps its connection.
    int fd2 = r.connect_client();
    r.serve_until([&r] { return r.server.counts().refused == 1; });
    char c;
    assert_true(recv(fd2, &c, 1, 0) <= 0);
    assert_int_equal(r.server.counts().refused, 1);
    assert_true(r.server.connected());
    close(fd2);
    close(fd);
    r.serve();
    assert_false(r.server.connected());
    assert_false(r.robot.motors_on());
}

static void test_faults(void **state)
{
    (void)state;
    Faults f;
    f.garbage_every = 3;
    f.corrupt_every = 4;
    f.drop_after_s = 3.0;
    Rig r(f);
    Reader rd;
    int fd = open_connection(r, rd);
    send_cmd(fd, HL_ARCOS_MOVE, 300, true);
    r.serve_until([&r] { return r.robot.base().moving(); });
    // 30 SIPs go out before the drop at 3 s of robot time (the stream opened at 0 s):
    // every 4th (7) fails its checksum, the garbage before every 3rd (10) is skipped.
    std::vector<hl_arcos_sip_t> sips = run(r, rd, fd, 35);
    const ServerCounts &c = r.server.counts();
    assert_int_equal(c.sips, 30);
    assert_int_equal(c.corrupt, 7);
    assert_int_equal(c.garbage, 10);
    assert_int_equal(c.drops, 1);
    assert_int_equal(c.faults(), 18);
    assert_true(rd.parser.bad_checksums >= 7);
    assert_true(sips.size() >= 20 && sips.size() <= 23);   // a rare phantom may eat one
    assert_true(rd.eof);
    assert_false(r.server.connected());
    uint16_t x = sips.back().x;
    assert_true(x > 250 && x <= 300);
    close(fd);
    // The robot stood still meanwhile; a new client finds it where it was.
    for (int k = 0; k < 10; k++) {
        uint64_t seq;
        assert_false(r.server.step(&seq));
    }
    Reader rd2;
    int fd2 = open_connection(r, rd2);
    std::vector<hl_arcos_sip_t> again = run(r, rd2, fd2, 12);
    assert_true(again.size() >= 8);
    assert_int_equal(again.back().type, HL_ARCOS_SIP_STOPPED);
    assert_int_equal(again.back().x, 300);
    assert_int_equal(r.server.counts().drops, 1);   // once
    close(fd2);
}

static void test_drop_every(void **state)
{
    (void)state;
    Faults f;
    f.drop_every_s = 1.5;
    Rig r(f);
    // Nobody connected for 3 s of robot time: the period starts at each connection, so
    // the first client is not dropped at once for the time that passed before it came.
    for (int k = 0; k < 30; k++) {
        uint64_t seq;
        assert_false(r.server.step(&seq));
    }
    assert_int_equal(r.server.counts().drops, 0);
    for (uint64_t round = 1; round <= 3; round++) {
        Reader rd;
        int fd = open_connection(r, rd);
        uint64_t before = r.server.counts().sips;
        // 15 SIP periods of 100 ms from the connection: the drop comes at the 16th step
        // (the handshake took no robot time), so 15 SIPs get out each time.
        std::vector<hl_arcos_sip_t> sips = run(r, rd, fd, 20);
        assert_int_equal(r.server.counts().sips - before, 15);
        assert_int_equal(sips.size(), 15);
        assert_int_equal(r.server.counts().drops, round);
        assert_true(rd.eof);
        assert_false(r.server.connected());
        close(fd);
    }
    assert_int_equal(r.server.counts().clients, 3);
    assert_int_equal(r.server.counts().faults(), 3);
}

// --drop-every's value: seconds of robot time, 0.1 up; others refused naming it.
static void test_drop_every_option(void **state)
{
    (void)state;
    SimOptions o;
    std::string err;
    const char *ok[] = {"houghloc-sim", "--drop-every", "2.5"};
    int rc = static_cast<int>(parse_options(3, const_cast<char **>(ok), &o, &err));
    assert_int_equal(rc, static_cast<int>(ParseResult::Run));
    assert_true(o.faults.drop_every_s == 2.5);
    for (const char *v : {"0", "0.05", "-1", "1e8", "x", ""}) {
        SimOptions o2;
        const char *bad[] = {"houghloc-sim", "--drop-every", v};
        rc = static_cast<int>(parse_options(3, const_cast<char **>(bad), &o2, &err));
        assert_int_equal(rc, static_cast<int>(ParseResult::Error));
        assert_true(err.find("--drop-every") == 0);
        assert_true(o2.faults.drop_every_s < 0.0);
    }
}

// --mute-after: from 2 s of robot time no SIP goes out, but the robot still obeys: a
// STOP sent to it then stops it, and is counted.
static void test_mute(void **state)
{
    (void)state;
    Faults f;
    f.mute_after_s = 2.0;
    Rig r(f);
    Reader rd;
    int fd = open_connection(r, rd);
    send_cmd(fd, HL_ARCOS_VEL, 200, true);
    r.serve_until([&r] { return r.robot.base().moving(); });
    std::vector<hl_arcos_sip_t> sips = run(r, rd, fd, 30);
    const ServerCounts &c = r.server.counts();
    assert_int_equal(c.sips, 20);       // 0.1 .. 2.0 s; none from the mute on
    assert_int_equal(sips.size(), 20);
    assert_int_equal(c.mutes, 1);
    assert_int_equal(c.faults(), 1);
    assert_true(r.server.connected());
    assert_true(r.robot.base().moving());   // muted, not stopped
    assert_int_equal(r.connection.muted_stops(), 0);
    send_cmd(fd, HL_ARCOS_STOP, 0, false);
    r.serve_until([&r] { return r.connection.muted_stops() == 1; });
    run(r, rd, fd, 20);                 // 2 s to brake
    assert_false(r.robot.base().moving());
    assert_true(rd.packets.empty());
    assert_int_equal(r.server.counts().sips, 20);
    close(fd);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_move_over_tcp),
        cmocka_unit_test(test_faults),
        cmocka_unit_test(test_drop_every),
        cmocka_unit_test(test_drop_every_option),
        cmocka_unit_test(test_mute),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
