package io.dtron.report;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.DelayPolicy;
import io.dtron.engine.TestResult;
import io.dtron.testsupport.Waits;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.Socket;
import java.net.URI;
import java.net.http.HttpClient;
import java.net.http.HttpRequest;
import java.net.http.HttpResponse;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/**
 * The live view over real loopback sockets, following real runs of the lamp in virtual time: a browser that reads
 * gets every update in order; a browser that stops reading loses updates, while the run records every event, at the
 * same times as a run nobody watches, with the same verdict.
 */
@Timeout(value = 120, unit = TimeUnit.SECONDS)
class LiveViewTest {
    /** The queue of the stalled browser: small, so that a short run overflows it and its socket. */
    private static final int QUEUE = 64;
    private static final Pattern SEQ = Pattern.compile("^data: \\{\"seq\":(\\d+),");

    @Test
    void aBrowserThatReadsGetsEveryUpdateInOrderAndTheState() throws Exception {
        RunRecord record = LampRuns.record();
        try (LiveView live = LiveView.start(record, InetAddress.getLoopbackAddress(), 0)) {
            HttpClient http = HttpClient.newHttpClient();
            List<String> lines = new ArrayList<>();
            CompletableFuture<Void> reading = CompletableFuture.runAsync(() -> {
                try {
                    http.send(HttpRequest.newBuilder(URI.create(live.url() + "events")).build(),
                            HttpResponse.BodyHandlers.ofLines()).body().takeWhile(l -> !l.equals("event: end"))
                            .forEach(lines::add);
                } catch (Exception e) {
                    throw new IllegalStateException(e);
                }
            });
            Waits.await("the browser follows the run").until(() -> live.browsers() == 1);
            TestResult result = LampRuns.run(record, 11, 3000);
            String state = http.send(HttpRequest.newBuilder(URI.create(live.url() + "state.json")).build(),
                    HttpResponse.BodyHandlers.ofString()).body();
            assertEquals(record.json(), state);
            live.close();
            reading.get(60, TimeUnit.SECONDS);
            List<Long> seqs = new ArrayList<>();
            for (String l : lines) {
                Matcher m = SEQ.matcher(l);
                if (m.find()) {
                    seqs.add(Long.parseLong(m.group(1)));
                }
            }
            assertEquals(0, live.droppedUpdates());
            assertFalse(seqs.isEmpty());
            for (int i = 0; i < seqs.size(); i++) {
                assertEquals(seqs.get(0) + i, seqs.get(i), "updates in order, none lost");
            }
            Matcher last = Pattern.compile("\"seq\":(\\d+)").matcher(state);
            assertTrue(last.find());
            assertEquals(Long.parseLong(last.group(1)), seqs.get(seqs.size() - 1), "the last update is the state's");
            assertTrue(lines.stream().anyMatch(l -> l.contains("\"verdict\":{\"verdict\":\"" + result.verdict())),
                    "the verdict reached the browser");
            assertTrue(lines.stream().filter(l -> l.contains("\"event\":[")).count() == record.eventCount(),
                    "every input and output reached the browser");
        }
    }

    @Test
    void aBrowserThatStopsReadingLosesUpdatesNeverTheRunsEvents() throws Exception {
        long seed = 5;
        long units = 400_000;
        RunRecord unwatched = LampRuns.record();
        TestResult alone = LampRuns.run(unwatched, seed, units, DelayPolicy.EAGER);
        // more than the browser's socket buffers (the kernel doubles the send buffer; the receive buffer and its
        // window are at most 64 KiB here) and its queue of updates (of 100 bytes at most) hold
        assertTrue(unwatched.json().length() > 2 * LiveView.SEND_BUFFER + 65536 + QUEUE * 100,
                "a run long enough to fill what a stalled browser holds: " + unwatched.json().length() + " bytes");
        RunRecord watched = LampRuns.record();
        try (LiveView live = LiveView.start(watched, InetAddress.getLoopbackAddress(), 0, QUEUE);
             Socket stalled = new Socket()) {
            stalled.setReceiveBufferSize(4096);
            stalled.connect(new InetSocketAddress(InetAddress.getLoopbackAddress(), live.port()));
            OutputStream request = stalled.getOutputStream();
            request.write("GET /events HTTP/1.1\r\nHost: localhost\r\n\r\n".getBytes(StandardCharsets.US_ASCII));
            request.flush();
            // the browser asked for the updates and never reads them
            Waits.await("the stalled browser is a follower").until(() -> live.browsers() == 1);
            TestResult result = LampRuns.run(watched, seed, units, DelayPolicy.EAGER);
            assertEquals(alone, result, "the same verdict, explanation, counts and end time");
            assertEquals(unwatched.json(), watched.json(), "every event at the same time as in the unwatched run");
            assertTrue(live.droppedUpdates() > 0, "the stalled browser lost updates");
            assertEquals(1, live.browsers(), "and is still connected: the run did not wait for it");
            assertFalse(stalled.isClosed());
        }
    }

    @Test
    void itListensOnLoopbackOnlyAsSsShows() throws Exception {
        RunRecord record = LampRuns.record();
        try (LiveView live = LiveView.start(record, InetAddress.getLoopbackAddress(), 0)) {
            Process ss = new ProcessBuilder("ss", "-ltn").redirectErrorStream(true).start();
            String listing = new String(ss.getInputStream().readAllBytes(), StandardCharsets.UTF_8);
            assertEquals(0, ss.waitFor());
            List<String> addresses = new ArrayList<>();
            for (String line : listing.lines().toList()) {
                String[] f = line.trim().split("\\s+");
                if (f.length > 3 && f[3].endsWith(":" + live.port())) {
                    addresses.add(f[3].substring(0, f[3].length() - (":" + live.port()).length()));
                }
            }
            assertFalse(addresses.isEmpty(), listing);
            for (String a : addresses) {
                assertTrue(a.equals("127.0.0.1") || a.equals("[::ffff:127.0.0.1]"), "loopback only: " + addresses);
            }
        }
    }
}
