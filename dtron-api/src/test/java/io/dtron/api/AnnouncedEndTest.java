package io.dtron.api;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.dtron.api.internal.TesterSide;
import io.dtron.testsupport.Waits;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/**
 * A member that joins during a run sees no run start, yet learns the end the run announced: the tester's answers to
 * its clock pings carry it, with the run's id, until the run stops; then they carry none.
 */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class AnnouncedEndTest {
    private final String cluster = TestClusters.uniqueName("announcedEnd");

    @Test
    void theTestersPongsCarryTheRunsAnnouncedEndUntilItsStop() throws Exception {
        try (Dtron tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").tester(true).build())) {
            TesterSide.of(tester).setRunId("r1");
            long zero = tester.currentTimeNanos();
            long end = zero + 30_000_000_000L;
            TesterSide.of(tester).sendRunStart(Dtron.RUN_START.constructValued(Map.of("timeunit", 1000)), zero, end);
            try (Dtron late = Dtron.connect(TestClusters.inJvm(cluster).memberName("late").build())) {
                TesterSide side = TesterSide.of(late);
                Waits.await("the tester's pong with the run's end").until(() -> side.announcedEnd().endNanos() != 0);
                assertEquals(new TesterSide.AnnouncedEnd("r1", end), side.announcedEnd());
                tester.send(Dtron.RUN_STOP.constructValued(Map.of()));
                // the pongs after the stop announce no end (the wait fails the test if none comes)
                Waits.await("a pong after the stop, without an end").until(() -> side.announcedEnd().endNanos() == 0);
            }
        }
    }
}
