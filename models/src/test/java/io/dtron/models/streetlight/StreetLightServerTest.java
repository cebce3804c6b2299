package io.dtron.models.streetlight;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.Waits;
import java.net.CookieManager;
import java.net.URI;
import java.net.http.HttpClient;
import java.net.http.HttpRequest;
import java.net.http.HttpResponse;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

/** The street-light web application over plain HTTP, as a browser would use it, without a browser. */
@Timeout(value = 30, unit = TimeUnit.SECONDS)
class StreetLightServerTest {
    private static final Pattern RESULT_ROW = Pattern.compile("<td class=\"controller\">(\\d+)</td>"
            + "<td class=\"state\">(\\w+)</td><td class=\"status\">(\\w+)</td>");

    private StreetLightServer server;

    @AfterEach
    void stop() {
        if (server != null) {
            server.close();
        }
    }

    /** One operator's browser: its own cookies, following redirects. */
    private final class Browser {
        private final HttpClient client = HttpClient.newBuilder().cookieHandler(new CookieManager())
                .followRedirects(HttpClient.Redirect.NORMAL).connectTimeout(Duration.ofSeconds(5)).build();

        HttpResponse<String> get(String path) throws Exception {
            return client.send(HttpRequest.newBuilder(URI.create(server.url() + path)).GET().build(),
                    HttpResponse.BodyHandlers.ofString());
        }

        HttpResponse<String> post(String path, String form) throws Exception {
            return client.send(HttpRequest.newBuilder(URI.create(server.url() + path))
                    .header("Content-Type", "application/x-www-form-urlencoded")
                    .POST(HttpRequest.BodyPublishers.ofString(form)).build(), HttpResponse.BodyHandlers.ofString());
        }

        void logIn(String user) throws Exception {
            HttpResponse<String> home = post("/login", "username=" + user + "&password=" + StreetLightServer.PASSWORD);
            assertEquals("/home", home.uri().getPath(), home.body());
        }

        /** Waits until the result page shows a final status; returns controller, state and status. */
        String[] finalResult() throws Exception {
            return Waits.await("a final status on the result page").until(() -> {
                String page = get("/result").body();
                Matcher m = RESULT_ROW.matcher(page);
                assertTrue(m.find(), page);
                return new String[] {m.group(1), m.group(2), m.group(3)};
            }, result -> !result[2].equals("PENDING"));
        }
    }

    @Test
    void operatorsLogInWithTheirPasswordAndPagesNeedALogin() throws Exception {
        server = new StreetLightServer(4, false).start();
        assertTrue(server.url().matches("http://127\\.0\\.0\\.1:\\d+"), server.url());
        Browser browser = new Browser();
        HttpResponse<String> anonymous = browser.get("/controllers");
        assertEquals("/login", anonymous.uri().getPath());
        HttpResponse<String> wrong = browser.post("/login", "username=user0&password=nope");
        assertTrue(wrong.body().contains("<p id=\"login-error\" class=\"error\">Wrong user name or password.</p>"),
                wrong.body());

        browser.logIn("user3");
        String list = browser.get("/controllers").body();
        assertTrue(list.contains("Logged in as <b id=\"current-user\">user3</b>"), list);
        assertTrue(list.contains("<input type=\"checkbox\" id=\"ctrl-3\" name=\"controller\" value=\"3\"></td>"
                + "<td><label for=\"ctrl-3\">Controller 3</label></td><td>Vabaduse</td>"), list);
        assertEquals("/login", browser.get("/logout").uri().getPath());
        assertEquals("/login", browser.get("/home").uri().getPath(), "logged out");
    }

    @Test
    void aSwitchedControllerConvergesAndTheResultPageSaysOk() throws Exception {
        server = new StreetLightServer(4, false).start();
        Browser browser = new Browser();
        browser.logIn("user1");
        HttpResponse<String> command = browser.post("/select", "controller=2");
        assertEquals("/command", command.uri().getPath());
        assertTrue(command.body().contains("<p id=\"selected\">Selected: Controller 2</p>"), command.body());
        HttpResponse<String> result = browser.post("/switch", "state=DIMMED");
        assertEquals("/result", result.uri().getPath());
        assertEquals(List.of("2", "Dimmed", "OK"), List.of(browser.finalResult()));
        assertTrue(browser.get("/controllers").body().contains("<td>Ülikooli</td><td class=\"state\">Dimmed</td>"));
    }

    @Test
    void controllersPollWithABase64StatusAndLearnTheRequestedState() throws Exception {
        server = new StreetLightServer(2, false).start();
        Browser controller = new Browser();
        String status = VirtualController.encode(Map.of("id", "1", "state", "ON"));
        HttpResponse<String> answer = controller.get("/api/poll?status=" + status);
        assertEquals(200, answer.statusCode());
        assertEquals(Map.of("command", "OFF"), VirtualController.decode(answer.body()));
        assertEquals(400, controller.get("/api/poll?status=not-base64!").statusCode());
        assertEquals(400, controller.get("/api/poll?status="
                + VirtualController.encode(Map.of("id", "9", "state", "ON"))).statusCode());
    }

    @ParameterizedTest(name = "session mix-up {0}")
    @ValueSource(booleans = {false, true})
    void concurrentOperatorsSeeTheirOwnControllersUnlessTheSessionsAreMixedUp(boolean mixUp) throws Exception {
        server = new StreetLightServer(4, mixUp).start();
        Browser first = new Browser();
        Browser second = new Browser();
        first.logIn("user0");
        second.logIn("user1");
        first.post("/select", "controller=0");
        second.post("/select", "controller=2");
        first.post("/switch", "state=ON");
        String[] seen = first.finalResult();
        assertEquals(mixUp ? "2" : "0", seen[0], "the controller user0's result page shows");
        assertEquals(List.of("On", "OK"), List.of(seen[1], seen[2]));
        assertEquals(mixUp, server.sessionMixUp());
    }

    @Test
    void theSystemPropertyTurnsTheMixUpOn() {
        System.setProperty(StreetLightServer.SESSION_MIX_UP_PROPERTY, "true");
        try {
            assertTrue(new StreetLightServer(1).sessionMixUp());
        } finally {
            System.clearProperty(StreetLightServer.SESSION_MIX_UP_PROPERTY);
        }
        assertFalse(new StreetLightServer(1).sessionMixUp());
    }
}
