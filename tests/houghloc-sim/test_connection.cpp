// test_connection.cpp - houghloc-sim's ARCOS connection over bytes (handshake, OPEN, CLOSE,
// bad packets).
#include <cstring>

#include "connection.hpp"

#include "rooms.hpp"

// cmocka last: its macros (fail, ...) clash with standard headers included after it.
#include "test_support.hpp"

using namespace hlsim;

namespace {

struct Rig {
    World world = six_metre_room();
    std::vector<std::string> lines;
    Log log{[this](const std::string &s) { lines.push_back(s); }};
    SimConfig cfg;
    SimRobot robot;
    Connection connection;
    std::vector<uint8_t> out;
    Rig() : cfg(config()), robot(world, cfg, Pose{}, log), connection(robot, log) {}
    static SimConfig config()
    {
        SimConfig c;
        sim_profile("pioneer3", &c.profile);
        return c;
    }
    void feed(const std::vector<uint8_t> &b) { connection.feed(b.data(), b.size(), &out); }
    int count(const char *what) const
    {
        int n = 0;
        for (const std::string &l : lines)
            n += l.find(what) != std::string::npos;
        return n;
    }
};

std::vector<uint8_t> none(uint8_t n)
{
    uint8_t b[HL_ARCOS_PACKET_MAX];
    std::size_t len = 0;
    assert_int_equal(hl_arcos_encode_none(b, sizeof b, n, &len), HL_OK);
    return std::vector<uint8_t>(b, b + len);
}

std::vector<uint8_t> with_int(uint8_t n, int32_t arg)
{
    uint8_t b[HL_ARCOS_PACKET_MAX];
    std::size_t len = 0;
    assert_int_equal(hl_arcos_encode_int(b, sizeof b, n, arg, &len), HL_OK);
    return std::vector<uint8_t>(b, b + len);
}

std::vector<uint8_t> framed(std::vector<uint8_t> payload)
{
    uint8_t b[HL_ARCOS_PACKET_MAX];
    std::size_t len = 0;
    assert_int_equal(hl_arcos_frame(b, sizeof b, payload.data(), payload.size(), &len), HL_OK);
    return std::vector<uint8_t>(b, b + len);
}

void handshake(Rig &r)
{
    for (uint8_t k = 0; k < 3; k++)
        r.feed(none(k));
    assert_int_equal(static_cast<int>(r.connection.state()),
                     static_cast<int>(Connection::State::Ready));
    r.out.clear();
}

}  // namespace

static void test_handshake_bytes(void **state)
{
    (void)state;
    Rig r;
    r.feed(none(HL_ARCOS_SYNC0));                // before begin(): no connection, no reply
    assert_true(r.out.empty());
    r.connection.begin();
    // SYNC0 and SYNC1 come back verbatim, here fed one byte at a time.
    for (uint8_t b : none(HL_ARCOS_SYNC0))
        r.connection.feed(&b, 1, &r.out);
    const std::vector<uint8_t> echo0 = {0xFA, 0xFB, 0x03, 0x00, 0x00, 0x00};
    assert_true(r.out == echo0);
    r.out.clear();
    r.feed(none(HL_ARCOS_SYNC1));
    const std::vector<uint8_t> echo1 = {0xFA, 0xFB, 0x03, 0x01, 0x00, 0x01};
    assert_true(r.out == echo1);
    r.out.clear();
    r.feed(none(HL_ARCOS_SYNC2));
    hl_arcos_parser_t p;
    hl_arcos_parser_init(&p);
    hl_arcos_packet_t pkt;
    std::size_t used = 0;
    assert_int_equal(hl_arcos_parse(&p, r.out.data(), r.out.size(), &used, &pkt), HL_OK);
    assert_int_equal(used, r.out.size());
    hl_arcos_robot_id_t id;
    assert_int_equal(hl_arcos_decode_sync2(&pkt, &id), HL_OK);
    assert_string_equal(id.name, "houghloc-sim");
    assert_string_equal(id.cls, "Pioneer");
    assert_string_equal(id.subclass, "pioneer3");
    assert_false(r.connection.streaming());
    // OPEN starts the stream; ENABLE reaches the robot.
    r.feed(none(HL_ARCOS_OPEN));
    assert_true(r.connection.streaming());
    r.feed(with_int(HL_ARCOS_ENABLE, 1));
    assert_true(r.robot.motors_on());
    assert_int_equal(r.connection.commands(), 2);
    assert_int_equal(r.connection.bad_commands(), 0);
}

static void test_out_of_order(void **state)
{
    (void)state;
    Rig r;
    r.connection.begin();
    r.feed(none(HL_ARCOS_SYNC1));                // SYNC1 first: ignored, counted
    r.feed(with_int(HL_ARCOS_MOVE, 100));        // a command before the handshake
    assert_true(r.out.empty());
    assert_int_equal(r.connection.bad_commands(), 2);
    assert_int_equal(r.count("SYNC0, SYNC1, SYNC2 order"), 1);   // logged once
    // SYNC0, SYNC1, then SYNC0 again starts over; the handshake still completes.
    r.feed(none(HL_ARCOS_SYNC0));
    r.feed(none(HL_ARCOS_SYNC1));
    r.feed(none(HL_ARCOS_SYNC0));
    r.feed(none(HL_ARCOS_SYNC1));
    r.feed(none(HL_ARCOS_SYNC2));
    assert_int_equal(static_cast<int>(r.connection.state()),
                     static_cast<int>(Connection::State::Ready));
    assert_int_equal(r.out.size(), 4 * 6 + 5 + 1 + 13 + 8 + 9);   // 4 echoes, the id
}

static void test_bad_commands(void **state)
{
    (void)state;
    Rig r;
    r.connection.begin();
    handshake(r);
    r.feed(none(HL_ARCOS_OPEN));
    r.feed(with_int(HL_ARCOS_ENABLE, 1));
    // Malformed: an integer argument one byte short.
    r.feed(framed({HL_ARCOS_MOVE, HL_ARCOS_ARGTYPE_POS, 0x10}));
    // Unsupported: command 99, twice (logged once), and ENABLE 2 (out of its range).
    r.feed(framed({99}));
    r.feed(framed({99}));
    r.feed(framed({HL_ARCOS_ENABLE, HL_ARCOS_ARGTYPE_POS, 2, 0}));
    // A bad checksum, and garbage between packets.
    std::vector<uint8_t> bad = with_int(HL_ARCOS_MOVE, 100);
    bad.back() ^= 0xFF;
    r.feed(bad);
    r.feed({0x01, 0x02, 0x03});
    assert_int_equal(r.connection.bad_commands(), 5);
    assert_true(r.connection.garbage_bytes() >= 3);
    assert_int_equal(r.count("malformed"), 1);
    assert_int_equal(r.count("(command 99)"), 1);
    assert_int_equal(r.count("bad checksum"), 1);
    // None of it was fatal: the next MOVE is taken and moves the robot.
    uint64_t taken = r.connection.commands();
    r.feed(with_int(HL_ARCOS_MOVE, 100));
    assert_int_equal(r.connection.commands(), taken + 1);
    assert_true(r.connection.streaming());
    hl_arcos_sip_t s{};
    for (int k = 0; k < 30 && s.type != HL_ARCOS_SIP_STOPPED; k++) {
        r.robot.heard();
        s = r.robot.step();
    }
    assert_int_equal(s.x, 100);
    // ARIA's OPEN with an argument is accepted.
    r.feed(framed({HL_ARCOS_OPEN, HL_ARCOS_ARGTYPE_POS, 1, 0}));
    assert_int_equal(r.connection.bad_commands(), 5);
}

static void test_close(void **state)
{
    (void)state;
    Rig r;
    r.connection.begin();
    handshake(r);
    std::vector<uint8_t> all = none(HL_ARCOS_OPEN);
    for (const auto &p : {with_int(HL_ARCOS_ENABLE, 1), with_int(HL_ARCOS_SONAR, 1),
                          with_int(HL_ARCOS_VEL, 200), none(HL_ARCOS_CLOSE),
                          with_int(HL_ARCOS_VEL, 300)})
        all.insert(all.end(), p.begin(), p.end());
    r.feed(all);                                 // one read holding everything
    assert_true(r.connection.closed());
    assert_false(r.robot.motors_on());           // CLOSE stops the robot
    assert_false(r.robot.sonar_on());
    assert_int_equal(r.connection.commands(), 5);   // the VEL after CLOSE is not taken
    assert_int_equal(r.robot.step().type, HL_ARCOS_SIP_STOPPED);
    r.connection.end();
    assert_int_equal(static_cast<int>(r.connection.state()),
                     static_cast<int>(Connection::State::Idle));
    // A new client starts at the handshake again.
    r.connection.begin();
    r.feed(none(HL_ARCOS_SYNC0));
    assert_int_equal(r.out.size(), 6);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_handshake_bytes),
        cmocka_unit_test(test_out_of_order),
        cmocka_unit_test(test_bad_commands),
        cmocka_unit_test(test_close),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
