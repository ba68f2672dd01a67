// server_rig.hpp - a houghloc-sim server on loopback for the tests: a world, the robot in
// it, its connection and server listening on a free port, all on the test's thread, and a
// client socket connected to it. Include after cmocka (it asserts).
#ifndef HOUGHLOC_TEST_SERVER_RIG_HPP
#define HOUGHLOC_TEST_SERVER_RIG_HPP

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>

#include <string>
#include <vector>

#include "server.hpp"

struct ServerRig {
    hlsim::World world;
    std::vector<std::string> lines;     // every line the simulator logged
    hlsim::Log log{[this](const std::string &s) { lines.push_back(s); }};
    hlsim::SimConfig cfg;
    hlsim::SimRobot robot;
    hlsim::Connection connection;
    hlsim::Server server;
    ServerRig(const hlsim::World &w, const hlsim::SimConfig &c, const hlsim::Pose &start,
              const hlsim::Faults &f, bool lockstep, uint64_t seed)
        : world(w), cfg(c), robot(world, cfg, start, log), connection(robot, log, lockstep),
          server(robot, connection, log, f, seed)
    {
        std::string err;
        assert_true(server.listen("127.0.0.1", 0, &err));
        assert_true(server.port() > 0);
    }
    // Serves the sockets for up to @p ms (until nothing happens for that long).
    void serve(int ms = 20)
    {
        struct pollfd pfd[2];
        std::size_t n = server.pollfds(pfd);
        if (poll(pfd, n, ms) > 0)
            server.handle(pfd, n);
    }
    // A client socket connected to the server (not yet accepted: serve() accepts it).
    int connect_client()
    {
        int fd = socket(AF_INET, SOCK_STREAM, 0);
        struct sockaddr_in a {};
        a.sin_family = AF_INET;
        a.sin_port = htons(server.port());
        inet_pton(AF_INET, "127.0.0.1", &a.sin_addr);
        assert_int_equal(connect(fd, reinterpret_cast<struct sockaddr *>(&a), sizeof a), 0);
        return fd;
    }
};

#endif
