// The tuning page's server with TLS (--tls-cert/--tls-key), as it must run
// off the loopback: HTTPS answers with the certificate given, a client
// that checks it against that certificate gets in with the secret and not
// without, plain HTTP gets nothing, and the session cookie is Secure.
// tests/data/tls holds a self-signed certificate for 127.0.0.1 and
// localhost and its key, made for these tests only (valid to 2126):
//   openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes
//     -subj /CN=127.0.0.1 -addext subjectAltName=IP:127.0.0.1,DNS:localhost
//     -days 36500 -keyout loopback.key -out loopback.crt   (one line)
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/serve/tuning_server_fixture.hpp"
#include "tools/serve/access_gate.hpp"
// Last: <resolv.h>, which it includes, defines the macro _res that Eigen's headers use as a name.
#include <httplib.h>

namespace tnv::serve {
namespace {

using namespace tnv::serve::testing;

const std::string kCert = TNV_SOURCE_DIR "/tests/data/tls/loopback.crt";
const std::string kKey = TNV_SOURCE_DIR "/tests/data/tls/loopback.key";

class PageTlsTest : public TuningServerTest {
 protected:
  void adjust(ServeOptions& o) const override {
    o.tls_cert = kCert;
    o.tls_key = kKey;
  }
  // A client that trusts exactly the test certificate and checks the name.
  std::unique_ptr<httplib::SSLClient> tls_client() const {
    auto c = std::make_unique<httplib::SSLClient>("127.0.0.1", port_);
    c->set_ca_cert_path(kCert.c_str());
    c->enable_server_certificate_verification(true);
    c->set_read_timeout(10, 0);
    return c;
  }
};

TEST_F(PageTlsTest, HttpsWithTheSecretGetsInAndWithoutItDoesNot) {
  EXPECT_EQ(server_->page_url("127.0.0.1", port_).rfind("https://", 0), 0u) << server_->page_url("127.0.0.1", port_);
  const auto c = tls_client();
  const httplib::Result ok = c->Get("/api/info", {{"Authorization", "Bearer " + server_->secret()}});
  ASSERT_TRUE(ok) << "TLS handshake or request failed: " << httplib::to_string(ok.error());
  EXPECT_EQ(ok->status, 200);
  const httplib::Result none = c->Get("/api/info");
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status, 401);
  const nlohmann::json before = server_->state_snapshot();
  const httplib::Result take = c->Post("/api/control/take", {{"Authorization", "Bearer " + std::string(64, '0')},
                                                             {"Origin", "https://127.0.0.1:" + std::to_string(port_)},
                                                             {"X-Tnv-Token", kTabA}},
                                       "", "application/json");
  ASSERT_TRUE(take);
  EXPECT_EQ(take->status, 401);
  EXPECT_EQ(server_->state_snapshot(), before);
}

TEST_F(PageTlsTest, PlainHttpToTheTlsPortGetsNoAnswer) {
  httplib::Client plain("127.0.0.1", port_);
  plain.set_read_timeout(5, 0);
  const httplib::Result r = plain.Get("/api/info", {{"Authorization", "Bearer " + server_->secret()}});
  EXPECT_FALSE(r && r->status == 200) << "the secret went over plain HTTP and was answered";
}

TEST_F(PageTlsTest, AClientThatTrustsAnotherCertificateRefusesTheServer) {
  httplib::SSLClient c("127.0.0.1", port_);
  c.set_ca_cert_path("/dev/null");  // trusts nothing
  c.enable_server_certificate_verification(true);
  const httplib::Result r = c.Get("/api/info", {{"Authorization", "Bearer " + server_->secret()}});
  EXPECT_FALSE(r) << "a certificate nobody vouched for was accepted";
}

TEST_F(PageTlsTest, ThePrintedUrlsSecretBecomesASecureCookie) {
  const std::string url = server_->page_url("127.0.0.1", port_);
  const auto c = tls_client();
  const httplib::Result r = c->Get(url.substr(url.find("/?token=")).c_str());
  ASSERT_TRUE(r) << httplib::to_string(r.error());
  EXPECT_EQ(r->status, 303);
  const std::string cookie = r->get_header_value("Set-Cookie");
  EXPECT_NE(cookie.find("; Secure"), std::string::npos) << cookie;
  EXPECT_NE(cookie.find("HttpOnly"), std::string::npos) << cookie;
}

TEST(PageTlsBind, OffTheLoopbackOnlyWithBothCertAndKey) {
  EXPECT_NE(bind_refusal("0.0.0.0", "", ""), "");
  EXPECT_NE(bind_refusal("192.168.1.5", kCert, ""), "");
  EXPECT_NE(bind_refusal("127.0.0.1", "", kKey), "");
  EXPECT_EQ(bind_refusal("0.0.0.0", kCert, kKey), "");
  EXPECT_EQ(bind_refusal("127.0.0.1", "", ""), "");
}

TEST(PageTlsBind, AKeyThatDoesNotMatchItsFileIsRefusedAtStart) {
  can_host::ConnectionOptions c;
  c.emu = true;
  std::vector<std::string> notes;
  auto connection = can_host::NodeConnection::open(c, notes);
  ServeOptions o;
  o.audit_path = "/dev/null";
  o.tls_cert = kCert;
  o.tls_key = kCert;  // a certificate is no key
  try {
    TuningServer server(connection->client(), connection->emulated(), o);
    FAIL() << "a server started with a certificate for its key";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("loopback.crt"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tnv::serve
