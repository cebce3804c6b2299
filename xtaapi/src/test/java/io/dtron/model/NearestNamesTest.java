package io.dtron.model;

import static org.junit.jupiter.api.Assertions.assertEquals;

import java.util.List;
import org.junit.jupiter.api.Test;

class NearestNamesTest {

    @Test
    void aSwapADropAndAnExtraCharacterAreOneEditEach() {
        assertEquals(1, NearestNames.distance("Trian", "Train"));
        assertEquals(1, NearestNames.distance("Crss", "Cross"));
        assertEquals(1, NearestNames.distance("lenn", "len"));
        assertEquals(2, NearestNames.distance("Gtae", "Gaet"));
        assertEquals(5, NearestNames.distance("", "Cross"));
    }

    @Test
    void onlyTheNearestAndAtMostThree() {
        List<String> processes = List.of("Train", "Gate", "Trains", "Tram");
        assertEquals(List.of("Train"), NearestNames.of("Trian", processes));
        assertEquals(List.of("Train(1)"),
                NearestNames.of("Trian(1)", List.of("Train(0)", "Train(1)", "Train(2)", "Train(3)", "Gate")));
        assertEquals(List.of("Train(0)", "Train(1)", "Train(2)"),
                NearestNames.of("Train(7)", List.of("Train(3)", "Train(2)", "Train(1)", "Train(0)", "Gate")));
        assertEquals(List.of("Gate", "gate"), NearestNames.of("Gatee", List.of("gate", "Gate", "date1")),
                "both one edit away, case ignored: the one nearer with case first");
        assertEquals(List.of("Gate"), NearestNames.of("gate", processes), "case is ignored");
        assertEquals(List.of(), NearestNames.of("Bridge", processes));
        // a one-letter name has no near names: any other letter would be a guess
        assertEquals(List.of(), NearestNames.of("x", List.of("y", "x1", "z")));
    }

    @Test
    void theHintIsEmptyOrQuotesEachName() {
        assertEquals(" (did you mean 'Cross'?)", NearestNames.hint("Crss", List.of("Far", "Appr", "Cross")));
        assertEquals(" (did you mean 'len' or 'lens'?)", NearestNames.hint("lenn", List.of("len", "lens", "open")));
        assertEquals(" (did you mean 'a1', 'a2' or 'a3'?)", NearestNames.hint("a0", List.of("a3", "a2", "a1", "a4")));
        assertEquals("", NearestNames.hint("Bridge", List.of("Train", "Gate")));
    }
}
