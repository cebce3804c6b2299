package io.dtron.models.ticker;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import io.dtron.engine.Event;
import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.TestInterface;
import io.dtron.models.VirtualRun;
import java.util.List;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;

/** The ticker against the timing and numbering of {@code ticker.xml}, in virtual time. */
class TickerSystemTest {
    private static final long MS = 1000;
    private static TestInterface ticker;

    @BeforeAll
    static void loadModel() throws ModelException {
        ticker = TestInterface.fromNames(
                ModelLoader.loadResource(TickerSystemTest.class.getClassLoader(), "io/dtron/models/ticker.xml"));
    }

    private static Event tick(int seq) {
        return Event.of("tick", "seq", seq);
    }

    @Test
    void ticksEveryTenUnitsNumberedFromOne() {
        VirtualRun run = new VirtualRun(new TickerSystem(), ticker, MS);
        run.runUntil(35);
        assertEquals(List.of(run.at(10, tick(1)), run.at(20, tick(2)), run.at(30, tick(3))), run.outputs());
    }

    @Test
    void resetRestartsThePeriodAndTheNumbering() {
        VirtualRun run = new VirtualRun(new TickerSystem(), ticker, MS);
        run.input(25, Event.of("reset"));
        run.runUntil(50);
        // the tick due at 30 is cancelled: the model's reset sets x = 0 and o_tick_seq = 0
        assertEquals(List.of(run.at(10, tick(1)), run.at(20, tick(2)), run.at(35, tick(1)), run.at(45, tick(2))),
                run.outputs());
    }

    @Test
    void sequenceNumbersWrapModulo1000() {
        VirtualRun run = new VirtualRun(new TickerSystem(), ticker, MS);
        run.runUntil(10_010);
        List<VirtualRun.Output> out = run.outputs();
        assertEquals(1001, out.size());
        assertEquals(List.of(run.at(9990, tick(999)), run.at(10_000, tick(0)), run.at(10_010, tick(1))),
                out.subList(998, 1001));
    }

    @Test
    void timeUnitComesFromTheRun() {
        VirtualRun run = new VirtualRun(new TickerSystem(), ticker, 250);
        run.runUntil(20);
        assertEquals(List.of(new VirtualRun.Output(2500, tick(1)), new VirtualRun.Output(5000, tick(2))),
                run.outputs());
    }

    @Test
    void slowVariantTicksEvery13UnitsBeyondTheModelsTwelve() {
        VirtualRun run = new VirtualRun(new TickerSystem("slow"), ticker, MS);
        run.runUntil(40);
        assertEquals(List.of(run.at(13, tick(1)), run.at(26, tick(2)), run.at(39, tick(3))), run.outputs());
    }

    @Test
    void stopEndsTheTicking() {
        VirtualRun run = new VirtualRun(new TickerSystem(), ticker, MS);
        run.runUntil(15);
        run.stop();
        run.runUntil(100);
        assertEquals(List.of(run.at(10, tick(1))), run.outputs());
    }

    @Test
    void variantsAreSelectedByName() {
        assertEquals("correct", new TickerSystem().variant());
        assertEquals("slow", new TickerSystem("slow").variant());
        assertEquals(List.of("correct", "slow"), TickerSystem.VARIANTS);
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> new TickerSystem("fast"));
        assertEquals("unknown variant 'fast' of io.dtron.models.ticker.TickerSystem; known variants: correct, slow",
                e.getMessage());
    }

    @Test
    void rejectsAnUnknownInputAndKeepsTicking() {
        TickerSystem system = new TickerSystem();
        VirtualRun run = new VirtualRun(system, ticker, MS);
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                () -> system.perform(Event.of("pause")));
        assertEquals("the ticker has no input 'pause'; its input is reset", e.getMessage());
        run.runUntil(10);
        assertEquals(List.of(run.at(10, tick(1))), run.outputs());
    }
}
