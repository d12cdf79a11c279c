#include "traci_server/traci_ego_link.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <optional>
#include <utility>  // before Asio: Boost 1.74's awaitable.hpp uses std::exchange without it

#include <boost/asio.hpp>

#include "traci_server/traci_session.hpp"

namespace orch::traci {

namespace {

namespace asio = boost::asio;
using tcp = asio::ip::tcp;
using Clock = std::chrono::steady_clock;

constexpr auto kPollSlice = std::chrono::milliseconds(100);  // how often a wait looks at Ctrl-C

// Clamped to [0, a century] (NaN: 0): nanoseconds in 64 bits overflow past ~292 years.
Clock::duration seconds(double s) {
  const double bounded = std::isnan(s) ? 0.0 : std::clamp(s, 0.0, 3.2e9);
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(bounded));
}

std::string endpoint_text(const tcp::endpoint& e) { return fmt::format("{}:{}", e.address().to_string(), e.port()); }

// How a wait ended.
enum class Wait { Done, TimedOut, Interrupted };

class TraciEgoLink final : public EgoLink {
 public:
  TraciEgoLink(const EgoServerOptions& options, std::unique_ptr<EgoWorld> world)
      : options_(options),
        world_(std::move(world)),
        session_(*world_, fmt::format("SUMO scenario orchestrator {} (ego TraCI server)", ORCH_VERSION)) {}

  std::string listen() override {
    boost::system::error_code ec;
    const auto address = asio::ip::make_address(options_.address, ec);
    if (ec) throw EgoError(fmt::format("--ego-address {}: not an IP address", options_.address));
    const tcp::endpoint where(address, static_cast<unsigned short>(options_.port));
    acceptor_.open(where.protocol(), ec);
    if (!ec) acceptor_.set_option(tcp::acceptor::reuse_address(true), ec);
    if (!ec) acceptor_.bind(where, ec);
    if (!ec) acceptor_.listen(1, ec);
    if (ec) throw EgoError(fmt::format("cannot listen for the ego plug-in on {}: {}", endpoint_text(where), ec.message()));
    report_.listen = endpoint_text(acceptor_.local_endpoint());
    return fmt::format("ego plug-in: TraCI server (API {}) on {}; waiting up to {:g} s for it after SUMO starts", 20,
                       report_.listen, options_.wait_s);
  }

  void exchange(double time) override {
    now_ = time;
    if (!socket_) connect();
    world_->new_step();
    Session::Next next;
    if (session_.stepping()) {
      if (time + 1e-6 < session_.target()) {  // simulationStep to a later time: keep going
        ++report_.steps_driven;
        return;
      }
      next = session_.resume();
    } else {
      next = read_and_handle();
    }
    while (true) {
      switch (next) {
        case Session::Next::Step: ++report_.steps_driven; return;
        case Session::Next::Reply:
          send(session_.take_reply());
          next = read_and_handle();
          break;
        case Session::Next::Close:
          send(session_.take_reply());
          drop("closed by the plug-in");
          throw EgoError(fmt::format("ego disconnected at t={:.3f} s: the plug-in closed the connection", now_));
      }
    }
  }

  void finish(const std::string& verdict, const std::string& reason) noexcept override {
    try {
      if (socket_ && session_.stepping()) {
        session_.end_run(fmt::format("the scenario run has ended: verdict {} ({})", verdict, reason));
        world_->new_step();
        const auto deadline = Clock::now() + seconds(std::min(options_.close_grace_s, options_.timeout_s));
        Session::Next next = session_.resume();
        // The plug-in sees the last step, then may ask a few more things and close.
        while (socket_ && next != Session::Next::Step) {
          write_all(session_.take_reply(), deadline);
          if (next == Session::Next::Close) {
            drop("closed by the plug-in at the end of the run");
            break;
          }
          const auto body = read_message(deadline);
          if (!body) break;
          next = session_.handle(*body);
        }
      }
    } catch (const std::exception&) {
      // The run is over either way; whatever the plug-in does now cannot change the verdict.
    }
    if (socket_) drop(report_.end.empty() ? "closed by the orchestrator at the end of the run" : report_.end);
    boost::system::error_code ignored;
    acceptor_.close(ignored);
  }

  [[nodiscard]] bool driving() const override { return socket_.has_value(); }

  [[nodiscard]] EgoLinkReport report() const override {
    EgoLinkReport r = report_;
    const traci::SessionStats stats = session_.stats();
    r.commands = stats.commands;
    r.client = stats.client;
    r.order = stats.order;
    return r;
  }

 private:
  // Runs the io_context until the started operation completes, the deadline passes or
  // Ctrl-C; then cancels it with `cancel` and lets the cancelled handler run.
  template <typename Cancel>
  Wait run_until(const bool& done, Clock::time_point deadline, Cancel cancel) {
    while (!done) {
      const auto now = Clock::now();
      const bool interrupted = options_.interrupted && options_.interrupted->load();
      if (now >= deadline || interrupted) {
        cancel();
        io_.restart();
        io_.run();
        return interrupted ? Wait::Interrupted : Wait::TimedOut;
      }
      io_.restart();
      io_.run_for(std::min<Clock::duration>(deadline - now, kPollSlice));
    }
    return Wait::Done;
  }

  void connect() {
    tcp::socket socket(io_);
    tcp::endpoint peer;
    bool done = false;
    boost::system::error_code ec;
    acceptor_.async_accept(socket, peer, [&](const boost::system::error_code& e) {
      ec = e;
      done = true;
    });
    const Wait w = run_until(done, Clock::now() + seconds(options_.wait_s), [&] { acceptor_.cancel(); });
    if (w == Wait::Interrupted) throw EgoError("interrupted while waiting for the ego plug-in to connect");
    if (w == Wait::TimedOut)
      throw EgoError(fmt::format("no ego plug-in connected to {} within {:g} s (--ego-wait)", report_.listen,
                                 options_.wait_s));
    if (ec) throw EgoError(fmt::format("accepting the ego plug-in on {} failed: {}", report_.listen, ec.message()));
    socket.set_option(tcp::no_delay(true), ec);  // lockstep: every reply is awaited
    socket.non_blocking(true, ec);                // reads try first, then wait (fill_inbox)
    socket_.emplace(std::move(socket));
    report_.peer = endpoint_text(peer);
    report_.connected_at = now_;
    // Only one plug-in drives the ego: nobody else gets in.
    boost::system::error_code ignored;
    acceptor_.close(ignored);
    world_->take_over_ego();
  }

  // Until `inbox_` holds at least `count` bytes; the error names what went wrong, "" on
  // success. Reads whatever the socket has (a whole message, or several, in one recv):
  // lockstep costs a few system calls per message, so one wait and one recv, not a wait
  // and a recv for the header and again for the body.
  std::string fill_inbox(std::size_t count, Clock::time_point deadline) {
    while (inbox_.size() < count) {
      boost::system::error_code ec;
      const std::size_t got = socket_->read_some(asio::buffer(read_chunk_), ec);  // non-blocking (connect)
      if (!ec) {
        inbox_.append(read_chunk_.data(), got);
        continue;
      }
      if (ec != asio::error::would_block && ec != asio::error::try_again)
        return ec == asio::error::eof ? "connection closed by the plug-in" : ec.message();
      bool done = false;
      socket_->async_wait(tcp::socket::wait_read, [&](const boost::system::error_code& e) {
        ec = e;
        done = true;
      });
      const Wait w = run_until(done, deadline, [&] { socket_->cancel(); });
      if (w == Wait::Interrupted) return "interrupted";
      if (w == Wait::TimedOut) return "timeout";
      if (ec) return ec.message();
    }
    return {};
  }

  // One message body, or nullopt at end of connection (`problem_` says why).
  std::optional<std::string> read_message(Clock::time_point deadline) {
    problem_ = fill_inbox(4, deadline);
    if (!problem_.empty()) return std::nullopt;
    std::array<std::uint8_t, 4> header{};
    std::copy_n(inbox_.begin(), 4, header.begin());
    std::size_t length = 0;
    try {
      length = message_body_length(header);
    } catch (const DecodeError& e) {
      std::string reply;
      append_status(reply, 0, 0xFF, std::string("malformed message: ") + e.what());
      protocol_error(frame_message(reply), e.what());
    }
    problem_ = fill_inbox(4 + length, deadline);
    if (!problem_.empty()) return std::nullopt;
    std::string body = inbox_.substr(4, length);
    inbox_.erase(0, 4 + length);
    return body;
  }

  Session::Next read_and_handle() {
    const auto body = read_message(Clock::now() + seconds(options_.timeout_s));
    if (!body) lost();
    try {
      return session_.handle(*body);
    } catch (const DecodeError& e) {
      protocol_error(session_.take_reply(), e.what());
    }
  }

  void write_all(const std::string& bytes, Clock::time_point deadline) {
    // A reply fits the socket's send buffer almost always: sent at once, without a wait.
    std::size_t sent = 0;
    boost::system::error_code ec;
    while (sent < bytes.size() && !ec) sent += socket_->write_some(asio::buffer(bytes.data() + sent, bytes.size() - sent), ec);
    if (sent == bytes.size()) return;
    if (ec != asio::error::would_block && ec != asio::error::try_again) {
      problem_ = ec.message();
      throw EgoError(problem_);
    }
    bool done = false;
    ec.clear();
    asio::async_write(*socket_, asio::buffer(bytes.data() + sent, bytes.size() - sent),
                      [&](const boost::system::error_code& e, std::size_t) {
      ec = e;
      done = true;
    });
    const Wait w = run_until(done, deadline, [&] { socket_->cancel(); });
    problem_ = w == Wait::Interrupted ? "interrupted" : w == Wait::TimedOut ? "timeout" : ec ? ec.message() : "";
    if (!problem_.empty()) throw EgoError(problem_);
  }

  void send(const std::string& bytes) {
    try {
      write_all(bytes, Clock::now() + seconds(options_.timeout_s));
    } catch (const EgoError&) {
      lost();
    }
  }

  // The connection is gone or silent: the run cannot go on without its driver.
  [[noreturn]] void lost() {
    if (problem_ == "interrupted") {
      drop("interrupted");
      throw EgoError(fmt::format("interrupted at t={:.3f} s while waiting for the ego plug-in", now_));
    }
    if (problem_ == "timeout") {
      drop("timeout");
      throw EgoError(fmt::format("ego timeout at t={:.3f} s: no message from the plug-in for {:g} s (--ego-timeout)",
                                 now_, options_.timeout_s));
    }
    drop("disconnected: " + problem_);
    throw EgoError(fmt::format("ego disconnected at t={:.3f} s: {}", now_, problem_));
  }

  [[noreturn]] void protocol_error(const std::string& reply, const std::string& what) {
    try {
      write_all(reply, Clock::now() + std::chrono::seconds(1));
    } catch (const EgoError&) {
      // It may already be gone; the error is the plug-in's either way.
    }
    drop("protocol error: " + what);
    throw EgoError(fmt::format("ego protocol error at t={:.3f} s: {}; connection closed", now_, what));
  }

  void drop(const std::string& how) {
    if (report_.end.empty()) report_.end = how;
    if (!socket_) return;
    boost::system::error_code ignored;
    socket_->shutdown(tcp::socket::shutdown_both, ignored);
    socket_->close(ignored);
    socket_.reset();
    inbox_.clear();
  }

  EgoServerOptions options_;
  std::unique_ptr<EgoWorld> world_;
  Session session_;
  asio::io_context io_;
  tcp::acceptor acceptor_{io_};
  std::optional<tcp::socket> socket_;
  std::string inbox_;  // bytes the plug-in sent that are not handled yet
  // What one recv fills; a member, not zeroed per call (that cost more than a step's TraCI work).
  std::array<char, 16384> read_chunk_;
  EgoLinkReport report_;
  std::string problem_;
  double now_ = 0;
};

}  // namespace

std::unique_ptr<EgoLink> make_traci_ego_link(const EgoServerOptions& options, std::unique_ptr<EgoWorld> world) {
  return std::make_unique<TraciEgoLink>(options, std::move(world));
}

}  // namespace orch::traci
