// server.cpp - TCP sockets, the SIP stream and fault injection for houghloc-sim.
#include "server.hpp"

#include <arpa/inet.h>
#include <cerrno>
#include <cstring>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

namespace hlsim {

namespace {

std::string peer_name(const struct sockaddr_in &a)
{
    char ip[INET_ADDRSTRLEN] = "?";
    inet_ntop(AF_INET, &a.sin_addr, ip, sizeof ip);
    return std::string(ip) + ":" + std::to_string(ntohs(a.sin_port));
}

}  // namespace

Server::Server(SimRobot &robot, Connection &connection, Log &log, const Faults &faults,
               uint64_t seed)
    : robot_(robot), connection_(connection), log_(log), faults_(faults),
      rng_(seed ^ 0x6761726261676521ULL)
{
}

Server::~Server()
{
    shutdown();
    end_capture();
}

bool Server::capture(const std::string &path, std::string *err)
{
    capture_ = std::fopen(path.c_str(), "wb");
    if (!capture_) {
        *err = "--capture: " + path + ": " + std::strerror(errno);
        return false;
    }
    capture_path_ = path;
    return true;
}

// The capture ends with its connection: a replay is one connection, from the handshake.
void Server::end_capture()
{
    if (!capture_)
        return;
    if (std::fclose(capture_) != 0)
        log_.line("--capture: %s: %s", capture_path_.c_str(), std::strerror(errno));
    else
        log_.line("--capture: %s written", capture_path_.c_str());
    capture_ = nullptr;   // later clients are not captured
}

bool Server::listen(const std::string &addr, int port, std::string *err)
{
    struct sockaddr_in a {};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<uint16_t>(port));
    if (inet_pton(AF_INET, addr.c_str(), &a.sin_addr) != 1) {
        *err = "--bind: '" + addr + "' is not an IPv4 address";
        return false;
    }
    int fd = socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) {
        *err = std::string("socket: ") + std::strerror(errno);
        return false;
    }
    int one = 1;
    setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    socklen_t alen = sizeof a;
    if (bind(fd, reinterpret_cast<struct sockaddr *>(&a), sizeof a) != 0 ||
        ::listen(fd, 4) != 0 ||
        getsockname(fd, reinterpret_cast<struct sockaddr *>(&a), &alen) != 0) {
        *err = addr + ":" + std::to_string(port) + ": " + std::strerror(errno);
        close(fd);
        return false;
    }
    listen_ = fd;
    port_ = ntohs(a.sin_port);
    return true;
}

std::size_t Server::pollfds(struct pollfd *pfd) const
{
    std::size_t n = 0;
    if (listen_ >= 0)
        pfd[n++] = {listen_, POLLIN, 0};
    if (client_ >= 0)
        pfd[n++] = {client_,
                    static_cast<short>((connection_.wants_input() ? POLLIN : 0) |
                                       (out_.empty() ? 0 : POLLOUT)),
                    0};
    return n;
}

void Server::handle(const struct pollfd *pfd, std::size_t n)
{
    for (std::size_t i = 0; i < n; i++) {
        if (pfd[i].revents == 0)
            continue;
        if (pfd[i].fd == listen_ && listen_ >= 0) {
            accept_client();
        } else if (pfd[i].fd == client_ && client_ >= 0) {
            if (pfd[i].revents & POLLOUT)
                flush();
            // A hang-up or an error is read at once (to its end); plain input only
            // while the connection wants it.
            if (client_ >= 0 && (pfd[i].revents & (POLLHUP | POLLERR)))
                read_client(true);
            else if (client_ >= 0 && (pfd[i].revents & POLLIN))
                read_client(false);
        }
    }
}

void Server::accept_client()
{
    struct sockaddr_in a {};
    socklen_t alen = sizeof a;
    int fd = accept4(listen_, reinterpret_cast<struct sockaddr *>(&a), &alen,
                     SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) {
        if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)
            log_.line("accept: %s", std::strerror(errno));
        return;
    }
    if (client_ >= 0) {
        counts_.refused++;
        log_.line("refused a second client from %s: one client at a time",
                  peer_name(a).c_str());
        close(fd);
        return;
    }
    int one = 1;
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);  // SIPs are small
    client_ = fd;
    accepted_utime_ = robot_.utime();
    out_.clear();
    counts_.clients++;
    connection_.begin();
    log_.line("client connected from %s", peer_name(a).c_str());
}

// Reads what the client sent while the connection wants it (@p all: everything, to the
// end of the connection).
void Server::read_client(bool all)
{
    uint8_t buf[4096];
    while (all || connection_.wants_input()) {
        ssize_t r = recv(client_, buf, sizeof buf, 0);
        if (r > 0) {
            connection_.feed(buf, static_cast<std::size_t>(r), &out_);
            if (connection_.closed()) {
                flush();
                close_client("the client sent CLOSE");
                return;
            }
            continue;
        }
        if (r == 0) {
            close_client("the client disconnected");
        } else if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
            std::string why = std::string("client connection: ") + std::strerror(errno);
            close_client(why.c_str());
        }
        break;
    }
    flush();
}

// After client input was carried out outside read_client (lockstep: the input held behind
// a period): a CLOSE among it ends the connection.
void Server::after_input()
{
    if (client_ >= 0 && connection_.closed()) {
        flush();
        close_client("the client sent CLOSE");
    }
}

void Server::flush()
{
    std::size_t off = 0;
    while (client_ >= 0 && off < out_.size()) {
        ssize_t w = send(client_, out_.data() + off, out_.size() - off,
                         MSG_NOSIGNAL | MSG_DONTWAIT);
        if (w > 0) {
            if (capture_ && std::fwrite(out_.data() + off, 1, static_cast<std::size_t>(w),
                                        capture_) != static_cast<std::size_t>(w)) {
                log_.line("--capture: %s: write failed; the capture stops here",
                          capture_path_.c_str());
                std::fclose(capture_);
                capture_ = nullptr;
            }
            off += static_cast<std::size_t>(w);
        } else if (w < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) {
            break;
        } else {
            std::string why = std::string("client connection: ") + std::strerror(errno);
            close_client(why.c_str());
            return;
        }
    }
    out_.erase(out_.begin(), out_.begin() + static_cast<std::ptrdiff_t>(off));
    if (out_.size() > kMaxBacklog)
        close_client("the client does not read its SIPs");
}

void Server::close_client(const char *why)
{
    if (client_ < 0)
        return;
    close(client_);
    client_ = -1;
    out_.clear();
    connection_.end();
    end_capture();
    log_.line("%s: connection closed; the robot is stopped and keeps its pose", why);
}

void Server::shutdown()
{
    close_client("shutting down");
    if (listen_ >= 0)
        close(listen_);
    listen_ = -1;
}

bool Server::queue_sip(const hl_arcos_sip_t &sip)
{
    if (muted_)
        return false;   // the period ran; its SIP goes nowhere
    uint64_t k = counts_.sips + 1;   // this SIP's place in the stream, from 1
    if (faults_.garbage_every > 0 && k % faults_.garbage_every == 0) {
        int64_t n = rng_.uniform_int(1, 64);
        // Lockstep, no sync byte: garbage that looked like a header could swallow the SIP
        // after it, which the client would then never answer, and the clock would stop.
        const int64_t top = connection_.lockstep() ? HL_ARCOS_HDR0 - 1 : 0xFF;
        for (int64_t i = 0; i < n; i++)
            out_.push_back(static_cast<uint8_t>(rng_.uniform_int(0, top)));
        counts_.garbage++;
        log_.line("fault: %lld garbage bytes before SIP %llu", static_cast<long long>(n),
                  static_cast<unsigned long long>(k - 1));
    }
    uint8_t buf[HL_ARCOS_PACKET_MAX];
    std::size_t len = 0;
    if (hl_arcos_encode_sip(buf, sizeof buf, &sip, &len) != HL_OK) {
        log_.once("encode-sip", "a SIP failed to encode: not sent (a bug)");
        return false;
    }
    corrupted_ = faults_.corrupt_every > 0 && k % faults_.corrupt_every == 0;
    if (corrupted_) {
        buf[len - 1] ^= 0x5A;   // the checksum's low byte
        counts_.corrupt++;
        log_.line("fault: SIP %llu sent with a wrong checksum",
                  static_cast<unsigned long long>(k - 1));
    }
    out_.insert(out_.end(), buf, buf + len);
    counts_.sips++;
    return true;
}

bool Server::step(uint64_t *seq)
{
    const bool lockstep = connection_.lockstep();
    period_muted_ = false;
    if (!may_step())
        return false;   // lockstep: no period granted, robot time stands
    const double t = static_cast<double>(robot_.utime()) / 1e6;
    if (!stalled_ && faults_.stall_after_s >= 0.0 && t >= faults_.stall_after_s) {
        stalled_ = true;
        counts_.stalls++;
        robot_.stall_wheels();
        log_.line("fault: the wheels stall from now on (--stall-after %g)", faults_.stall_after_s);
    }
    if (!muted_ && faults_.mute_after_s >= 0.0 && t >= faults_.mute_after_s) {
        muted_ = true;
        counts_.mutes++;
        connection_.set_muted();
        log_.line("fault: no SIP goes out from now on; commands are still read and obeyed "
                  "(--mute-after %g)", faults_.mute_after_s);
    }
    if (!dropped_ && faults_.drop_after_s >= 0.0 && t >= faults_.drop_after_s &&
        client_ >= 0) {
        dropped_ = true;
        counts_.drops++;
        close_client("fault: dropping the client (--drop-after)");
    }
    // Timed from each connection's start, not from 0: a client that takes a while to come
    // back still gets its full period, so every connection can do some work.
    if (faults_.drop_every_s > 0.0 && client_ >= 0 &&
        static_cast<double>(robot_.utime() - accepted_utime_) / 1e6 >= faults_.drop_every_s) {
        counts_.drops++;
        close_client("fault: dropping the client (--drop-every)");
    }
    if (lockstep && client_ < 0)
        return false;   // dropped by a fault just now: no client, no period
    hl_arcos_sip_t sip = robot_.step();
    counts_.teleports = robot_.teleports();   // the robot schedules those: they wait for it
    if (client_ < 0 || !connection_.streaming())
        return false;
    *seq = counts_.sips;
    bool queued = queue_sip(sip);
    period_muted_ = muted_;
    if (lockstep) {
        connection_.period_done(&out_);   // what the client sent after this grant
        if (queued && corrupted_)
            connection_.grant_unanswerable();
        after_input();
    }
    flush();
    return queued;
}

}  // namespace hlsim
