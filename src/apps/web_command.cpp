#include "apps/web_command.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "apps/console_command.hpp"
#include "telear/web/web_server.hpp"

namespace telear::cli {

int run_web(const web::WebOptions& given, const geometry::RobotSelection& arm, std::ostream& out,
            std::ostream& err) {
  web::WebOptions options = given;
  options.arm = arm.robot_spec();
  auto geometry = arm.geometry_options();
  if (!geometry) {
    err << "telear web: " << geometry.error().message << "\n";
    return 2;
  }
  options.geometry = *geometry;
  if (options.robot.empty() != options.vision.empty()) {
    err << "telear web: give both --robot and --vision, or neither (the embedded simulated "
           "servers)\n";
    return 2;
  }
  if (options.tls_cert_file.empty() != options.tls_key_file.empty()) {
    err << "telear web: HTTPS needs both --tls-cert and --tls-key\n";
    return 2;
  }
  if (!options.start_local_servers) options.start_local_servers = simulated_local_servers();
  // The servers' logs go to stderr: stdout's first lines are the address and the token, which
  // scripts read.
  spdlog::set_default_logger(std::make_shared<spdlog::logger>(
      "", std::make_shared<spdlog::sinks::stderr_color_sink_mt>()));
  auto server = web::WebServer::create(options, err);
  if (!server) {
    err << "telear web: " << server.error().message << "\n";
    return 2;
  }
  // Scripts and tests read these two lines: the address first, then the token to type.
  out << "listening on " << (*server)->url() << "\n";
  if (!(*server)->local_token().empty()) out << "token: " << (*server)->local_token() << "\n";
  out.flush();
  (*server)->run_until_signal();
  return 0;
}

}  // namespace telear::cli
