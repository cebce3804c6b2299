package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/** {@code dtron verify --delta / --delta-from}: re-verification of the Delta-extended model in one command. */
class VerifyDeltaTest {
    /** A port that answers a request within 8 units of it, and a user that asks every 4 units or more. */
    private static final String PORT = """
            chan i_req, o_resp;
            process Port() {
                clock x;
                state Idle, Serving { x <= 8 };
                init Idle;
                trans Idle -> Serving { sync i_req?; assign x = 0; },
                      Serving -> Idle { guard x >= 2; sync o_resp!; };
            }
            process User() {
                clock u;
                state Idle, Asked;
                init Idle;
                trans Idle -> Asked { guard u > 3; sync i_req!; assign u = 0; },
                      Asked -> Idle { sync o_resp?; };
            }
            system Port, User;
            """;
    /** Holds in the model as written: the invariant x <= 8 bounds the wait. */
    private static final String ANSWER_WITHIN_8 = "A[] not (Port.Serving and Port.x > 8)";

    @Test
    void theDeltaExtendedModelIsVerifiedWithItsWidenedBounds(@TempDir Path dir) throws Exception {
        Path model = Files.writeString(dir.resolve("port.xta"), PORT);
        CommandRun plain = CommandRun.of("verify", model.toString(), "--query", ANSWER_WITHIN_8);
        assertEquals(0, plain.exit(), plain.out() + plain.err());

        // 0 to 3 ms of delay on the response at 1 ms per unit: the invariant widens to x <= 8 + 3, and the property
        // of the model as written no longer holds of what the tester observes
        CommandRun widened = CommandRun.of("verify", model.toString(), "--query", ANSWER_WITHIN_8, "--delta",
                "resp=0..3000", "--timeunit", "1000");
        assertEquals(2, widened.exit(), widened.out() + widened.err());
        assertTrue(widened.out().contains("dtron verify: the Delta-extended model: 1 clock bound widened by --delta"
                + " resp=0..3000 at 1000 us per time unit"), widened.out());
        assertTrue(widened.out().contains("NOT satisfied"), widened.out());
        CommandRun observed = CommandRun.of("verify", model.toString(), "--query",
                "A[] not (Port.Serving and Port.x > 11)", "--delta", "resp=0..3000", "--timeunit", "1000");
        assertEquals(0, observed.exit(), observed.out() + observed.err());
    }

    @Test
    void badDelaysAndStrayOptionsAreClearErrors(@TempDir Path dir) throws Exception {
        Path model = Files.writeString(dir.resolve("port.xta"), PORT);
        CommandRun unknown = CommandRun.of("verify", model.toString(), "--query", ANSWER_WITHIN_8, "--delta",
                "o_resp=0..3000");
        assertEquals(1, unknown.exit());
        assertTrue(unknown.err().contains("dtron verify: --delta o_resp=0..3000: unknown channel 'o_resp' (name it"
                + " 'resp', its name on the bus, without i_/o_)"), unknown.err());
        CommandRun stray = CommandRun.of("verify", model.toString(), "--query", ANSWER_WITHIN_8, "--timeunit", "1000");
        assertEquals(1, stray.exit());
        assertTrue(stray.err().contains("--interface and --timeunit go with the delays of --delta or --delta-from"),
                stray.err());
        CommandRun noReport = CommandRun.of("verify", model.toString(), "--delta-from",
                dir.resolve("none.json").toString());
        assertEquals(1, noReport.exit());
        assertTrue(noReport.err().contains("none.json: no such file"), noReport.err());
    }
}
