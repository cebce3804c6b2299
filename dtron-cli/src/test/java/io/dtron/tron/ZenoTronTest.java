package io.dtron.tron;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.cli.CommandRun;
import java.io.InputStream;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code dtron tron} with a model whose environment may give inputs with no time between them ({@code
 * zeno-lamp.xta}), in real time, against the lamp as a TRON socket adapter ({@link TronAdapterClient}): the correct
 * lamp passes with TRON's {@code -P SHORT,LONG}; a lamp that configures, starts and then never answers fails at its
 * deadline, naming it.
 */
@Timeout(value = 120, unit = TimeUnit.SECONDS, threadMode = Timeout.ThreadMode.SEPARATE_THREAD)
class ZenoTronTest {
    private static final long UNIT = 10_000;

    @TempDir
    Path dir;

    /** Runs {@code dtron tron -P 1,5 ... MODEL -- 127.0.0.1 PORT} against the lamp listening on PORT. */
    private CommandRun againstLamp(boolean answers) throws Exception {
        Path model = dir.resolve("zeno-lamp.xta");
        try (InputStream in = ZenoTronTest.class.getResourceAsStream("/io/dtron/cli/zeno-lamp.xta")) {
            Files.copy(in, model);
        }
        try (ServerSocket server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            String port = Integer.toString(server.getLocalPort());
            CompletableFuture<CommandRun> run = CompletableFuture.supplyAsync(() -> CommandRun.of("tron", "-P", "1,5",
                    "-X", "5", "-S", dir.resolve("stats.txt").toString(), model.toString(), "--", "127.0.0.1", port));
            try (TronAdapterClient lamp = TronAdapterClient.accept(server, TronAdapterClient.TimeMode.REAL_TIME)) {
                int grasp = lamp.registerInput("grasp");
                lamp.registerInput("release");
                int level = lamp.registerOutput("level");
                lamp.setTimeUnit(UNIT);
                lamp.setTimeout(200);
                AtomicBoolean grasped = new AtomicBoolean();
                lamp.start((channel, values) -> {
                    if (answers && channel == grasp && grasped.compareAndSet(false, true)) {
                        lamp.schedule(2 * UNIT, () -> lamp.reportOutput(level));
                    }
                });
                return run.get(60, TimeUnit.SECONDS);
            }
        }
    }

    @Test
    void theCorrectLampPassesWithShortAndLongDelays() throws Exception {
        CommandRun r = againstLamp(true);
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("dtron tron: the environment may give inputs with no time passing (Zeno): the"
                + " cycle Ready -> Ready of User may take no time"), r.out());
        assertTrue(r.out().contains("TEST PASSED: the timeout of 200 time units was reached"), r.out());
        assertFalse(r.err().contains("note: -P"), r.err());
    }

    @Test
    void aLampThatNeverAnswersFailsAtItsDeadlineNotAsAnUnfinishedFrame() throws Exception {
        CommandRun r = againstLamp(false);
        assertEquals(2, r.exit(), r.out() + r.err());
        Matcher m = Pattern.compile("TEST FAILED: no output came by t=(\\d+\\.\\d+): the model required")
                .matcher(r.out());
        assertTrue(m.find(), r.out());
        assertTrue(r.out().contains("level between "), r.out());
        assertFalse(r.out().contains("frame"), r.out());
        // the verdict's own time (microseconds, in the statistics line): within a second of the deadline
        String stats = Files.readString(dir.resolve("stats.txt"));
        Matcher at = Pattern.compile("5 FAILED \\d+ 0 (\\d+)").matcher(stats);
        assertTrue(at.find(), stats);
        assertTrue(Long.parseLong(at.group(1)) - Double.parseDouble(m.group(1)) * UNIT < 1_000_000, r.out() + stats);
    }
}
