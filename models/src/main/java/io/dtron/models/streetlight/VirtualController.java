package io.dtron.models.streetlight;

import java.io.IOException;
import java.net.URI;
import java.net.http.HttpClient;
import java.net.http.HttpRequest;
import java.net.http.HttpResponse;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.Base64;
import java.util.LinkedHashMap;
import java.util.Map;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * A simulated street-light controller, as in the case study: it polls the server with its status as a Base64
 * string ({@code id=3;state=ON;lamps=24;uptime=57} encoded), and the server answers with the state requested of
 * it ({@code command=DIMMED} encoded). Its relays switch between two polls: a new state is reported at the next
 * poll, so the controller converges to the requested state one poll after it learnt it.
 */
final class VirtualController {
    private static final Logger LOG = LoggerFactory.getLogger(VirtualController.class);
    private static final Duration REQUEST_TIMEOUT = Duration.ofSeconds(2);

    private final int id;
    private final int lamps;
    private final URI server;
    private final HttpClient client;
    private final long started = System.nanoTime();
    private LightState state = LightState.OFF;

    VirtualController(int id, URI server, HttpClient client) {
        this.id = id;
        this.lamps = 12 + 4 * (id % 5);
        this.server = server;
        this.client = client;
    }

    /** One poll: reports the status, learns the requested state and switches to it. Called on one thread. */
    void poll() {
        String status = encode(statusFields());
        HttpRequest request = HttpRequest.newBuilder(server.resolve("/api/poll?status=" + status))
                .timeout(REQUEST_TIMEOUT).GET().build();
        try {
            HttpResponse<String> response = client.send(request, HttpResponse.BodyHandlers.ofString());
            if (response.statusCode() != 200) {
                LOG.warn("Controller {}: the server answered {} {}", id, response.statusCode(), response.body());
                return;
            }
            String command = decode(response.body().trim()).get("command");
            LightState requested = command == null ? null : LightState.parse(command).orElse(null);
            if (requested == null) {
                LOG.warn("Controller {}: no command in the server's answer '{}'", id, response.body());
            } else if (requested != state) {
                LOG.debug("Controller {} switches from {} to {}", id, state, requested);
                state = requested;
            }
        } catch (IOException e) {
            LOG.debug("Controller {} could not poll: {}", id, e.toString());
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    private Map<String, String> statusFields() {
        Map<String, String> fields = new LinkedHashMap<>();
        fields.put("id", Integer.toString(id));
        fields.put("state", state.name());
        fields.put("lamps", Integer.toString(lamps));
        fields.put("uptime", Long.toString((System.nanoTime() - started) / 1_000_000_000L));
        return fields;
    }

    /** Encodes {@code key=value;...} as URL-safe Base64. */
    static String encode(Map<String, String> fields) {
        StringBuilder text = new StringBuilder();
        fields.forEach((k, v) -> text.append(text.length() == 0 ? "" : ";").append(k).append('=').append(v));
        return Base64.getUrlEncoder().encodeToString(text.toString().getBytes(StandardCharsets.UTF_8));
    }

    /**
     * Decodes URL-safe Base64 {@code key=value;...}.
     *
     * @throws IllegalArgumentException if it is no such string
     */
    static Map<String, String> decode(String base64) {
        String text = new String(Base64.getUrlDecoder().decode(base64), StandardCharsets.UTF_8);
        Map<String, String> fields = new LinkedHashMap<>();
        for (String part : text.split(";")) {
            int eq = part.indexOf('=');
            if (eq <= 0) {
                throw new IllegalArgumentException("no key=value: '" + part + "'");
            }
            fields.put(part.substring(0, eq), part.substring(eq + 1));
        }
        return fields;
    }
}
