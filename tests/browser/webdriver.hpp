#pragma once
// A headless Chromium driven through Debian's chromedriver (W3C WebDriver over HTTP on
// loopback), for tests that open the reports as a person would: load the page, move its
// controls, read back what it shows, collect the browser console.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <chrono>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "support/cli_runner.hpp"

namespace orch::test {

inline constexpr const char* kChromium = "/usr/bin/chromium";
inline constexpr const char* kChromedriver = "/usr/bin/chromedriver";

// Empty when the browser can run here; else what is missing (scripts/setup.sh installs it).
inline std::string browser_missing() {
  for (const char* p : {kChromium, kChromedriver})
    if (!std::filesystem::exists(p)) return std::string(p) + " is missing (scripts/setup.sh installs chromium and chromium-driver)";
  return "";
}

class Browser {
 public:
  // Starts chromedriver on a free loopback port and opens one headless Chromium session
  // with a fresh profile in `profile_dir`, no network services, `width` x `height` window.
  Browser(const std::filesystem::path& profile_dir, int width = 1400, int height = 1000) {
    port_ = free_port();
    driver_ = ::fork();
    if (driver_ == 0) {
      const std::string port_arg = "--port=" + std::to_string(port_);
      ::setpgid(0, 0);
      // chromedriver's own chatter stays out of the test's output.
      std::freopen("/dev/null", "w", stdout);
      ::execl(kChromedriver, kChromedriver, port_arg.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    wait_until_ready();
    const nlohmann::json args = {"--headless=new", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                                 "--disable-component-update", "--disable-sync", "--no-first-run",
                                 "--disable-dev-shm-usage", "--user-data-dir=" + profile_dir.string(),
                                 "--window-size=" + std::to_string(width) + "," + std::to_string(height)};
    const nlohmann::json caps = {
        {"capabilities",
         {{"alwaysMatch",
           {{"browserName", "chrome"},
            {"goog:chromeOptions", {{"binary", kChromium}, {"args", args}}},
            {"goog:loggingPrefs", {{"browser", "ALL"}}}}}}}};
    session_ = request("POST", "/session", caps)["value"]["sessionId"].get<std::string>();
  }
  ~Browser() {
    try {
      if (!session_.empty()) request("DELETE", "/session/" + session_, nullptr);
    } catch (const std::exception&) {
    }
    if (driver_ > 0) {
      ::kill(-driver_, SIGTERM);
      ::waitpid(driver_, nullptr, 0);
    }
  }
  Browser(const Browser&) = delete;
  Browser& operator=(const Browser&) = delete;

  void open(const std::filesystem::path& file) {
    command("POST", "url", {{"url", "file://" + std::filesystem::absolute(file).string()}});
  }
  // Runs `script` (a function body; `arguments` holds `args`) in the page and returns its value.
  nlohmann::json eval(const std::string& script, const nlohmann::json& args = nlohmann::json::array()) {
    return command("POST", "execute/sync", {{"script", script}, {"args", args}});
  }
  // The browser console since the last call: [{level, message, timestamp, source}].
  nlohmann::json console() { return command("POST", "se/log", {{"type", "browser"}}); }
  // Console entries of level SEVERE (errors, uncaught exceptions, failed loads).
  std::vector<std::string> console_errors() {
    std::vector<std::string> out;
    for (const auto& e : console())
      if (e.value("level", "") == "SEVERE") out.push_back(e.value("message", ""));
    return out;
  }
  void resize(int width, int height) { command("POST", "window/rect", {{"width", width}, {"height", height}}); }
  // PNG bytes of the viewport.
  std::string screenshot() { return base64_decode(command("GET", "screenshot", nullptr).get<std::string>()); }

 private:
  nlohmann::json command(const std::string& method, const std::string& what, const nlohmann::json& body) {
    return request(method, "/session/" + session_ + "/" + what, body)["value"];
  }

  nlohmann::json request(const std::string& method, const std::string& target, const nlohmann::json& body) {
    namespace http = boost::beast::http;
    boost::asio::io_context io;
    boost::asio::ip::tcp::socket socket(io);
    socket.connect({boost::asio::ip::make_address("127.0.0.1"), static_cast<unsigned short>(port_)});
    http::request<http::string_body> req(http::string_to_verb(method), target, 11);
    req.set(http::field::host, "127.0.0.1");
    req.set(http::field::content_type, "application/json");
    if (!body.is_null()) req.body() = body.dump();
    req.prepare_payload();
    http::write(socket, req);
    boost::beast::flat_buffer buffer;
    http::response<http::string_body> res;
    http::read(socket, buffer, res);
    boost::system::error_code ignored;
    socket.shutdown(boost::asio::ip::tcp::socket::shutdown_both, ignored);
    const auto j = nlohmann::json::parse(res.body());
    if (res.result_int() != 200)
      throw std::runtime_error("webdriver " + method + " " + target + ": " + std::to_string(res.result_int()) + " " +
                               j.dump().substr(0, 2000));
    return j;
  }

  void wait_until_ready() {
    for (int i = 0; i < 200; ++i) {
      try {
        if (request("GET", "/status", nullptr)["value"].value("ready", false)) return;
      } catch (const std::exception&) {
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    throw std::runtime_error("chromedriver did not start");
  }

  static int free_port() {
    boost::asio::io_context io;
    boost::asio::ip::tcp::acceptor a(io, {boost::asio::ip::make_address("127.0.0.1"), 0});
    return a.local_endpoint().port();
  }

  static std::string base64_decode(const std::string& in) {
    static const std::string chars = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    int val = 0, bits = -8;
    for (const char c : in) {
      const auto p = chars.find(c);
      if (p == std::string::npos) continue;  // padding, line breaks
      val = (val << 6) + static_cast<int>(p);
      bits += 6;
      if (bits >= 0) {
        out.push_back(static_cast<char>((val >> bits) & 0xFF));
        bits -= 8;
      }
    }
    return out;
  }

  int port_ = 0;
  pid_t driver_ = -1;
  std::string session_;
};

// A test with a fresh browser (own profile folder); fails naming what is missing when
// Chromium or chromedriver is not installed.
class BrowserTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const auto missing = browser_missing(); !missing.empty()) FAIL() << missing;
    browser_ = std::make_unique<Browser>(profile_ / "chromium");
  }
  TempDir profile_;
  std::unique_ptr<Browser> browser_;
};

}  // namespace orch::test
