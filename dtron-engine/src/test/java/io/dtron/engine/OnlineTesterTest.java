package io.dtron.engine;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.util.ArrayList;
import java.util.List;
import org.junit.jupiter.api.Test;

class OnlineTesterTest {

    /** A ticker that must tick every 8..12 units, numbering its ticks; the environment may reset it. */
    static final String TICKER = """
            const int P = 10; const int T = 2;
            chan i_reset, o_tick;
            int[0,999] o_tick_seq;
            process Ticker() {
                clock x;
                state Running { x <= P + T };
                init Running;
                trans Running -> Running { guard x >= P - T; sync o_tick!; assign o_tick_seq = (o_tick_seq + 1) % 1000, x = 0; },
                      Running -> Running { sync i_reset?; assign x = 0, o_tick_seq = 0; };
            }
            process Env() {
                clock e;
                state Watching;
                init Watching;
                trans Watching -> Watching { guard e >= 25; sync i_reset!; assign e = 0; },
                      Watching -> Watching { sync o_tick?; };
            }
            system Ticker, Env;
            """;

    /** Ticks every {@code period} units; restarts on reset. */
    static final class Ticker implements Adapter {
        private final long period;
        private AdapterContext context;
        private TestClock.Scheduled next;
        private int seq;

        Ticker(long period) {
            this.period = period;
        }

        @Override
        public void start(AdapterContext context) {
            this.context = context;
            arm();
        }

        private void arm() {
            next = context.clock().schedule(period * context.timeUnitMicros(), () -> {
                seq = (seq + 1) % 1000;
                context.report(Event.of("tick", "seq", seq));
                arm();
            });
        }

        @Override
        public void perform(Event input) {
            next.cancel();
            seq = 0;
            arm();
        }
    }

    private static TestResult run(Adapter adapter, long seed, List<String> trace) throws Exception {
        Network n = ModelLoader.load("ticker.xta", TICKER);
        OnlineTester tester = new OnlineTester(n, TestInterface.fromNames(n), adapter,
                TestOptions.defaults(seed).withTimeout(500));
        tester.addListener(new TestListener() {
            @Override
            public void inputApplied(Event input, long micros) {
                trace.add(micros + " in " + input);
            }

            @Override
            public void outputObserved(Event output, long micros) {
                trace.add(micros + " out " + output);
            }
        });
        return tester.run();
    }

    @Test
    void aCorrectTickerPasses() throws Exception {
        List<String> trace = new ArrayList<>();
        TestResult r = run(new Ticker(10), 1, trace);
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation() + "\n" + String.join("\n", trace));
        assertTrue(r.outputs() > 20, r.toString());
        assertTrue(r.inputs() > 0, r.toString());
    }

    @Test
    void aSlowTickerFails() throws Exception {
        List<String> trace = new ArrayList<>();
        TestResult r = run(new Ticker(13), 1, trace);
        assertEquals(Verdict.FAILED, r.verdict(), r.explanation() + "\n" + String.join("\n", trace));
        System.out.println(r.explanation());
    }
}
