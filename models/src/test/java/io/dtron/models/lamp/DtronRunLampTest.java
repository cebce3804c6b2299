package io.dtron.models.lamp;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.cli.DtronCommand;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.file.Path;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;

/** The command, {@code dtron run LightContr.xml --interface LightContr.trn --sut ... --virtual-time}. */
class DtronRunLampTest {

    @ParameterizedTest(name = "{0}")
    @CsvSource({"correct, 0, PASSED", "late, 2, FAILED", "early, 2, FAILED", "wrong-level, 2, FAILED",
            "missing, 2, FAILED"})
    void theCommandLineGivesTronsExitCodes(String variant, int exit, String verdict) {
        Path tron = Path.of(System.getProperty("dtron.shared", "../../shared"), "models", "tron");
        StringWriter out = new StringWriter();
        StringWriter err = new StringWriter();
        int code = DtronCommand.run(new String[] {"run", tron.resolve("LightContr.xml").toString(), "--interface",
                tron.resolve("LightContr.trn").toString(), "--sut", SmartLamp.class.getName() + ":" + variant,
                "--virtual-time", "--seed", "1"}, new PrintWriter(out), new PrintWriter(err));
        assertEquals(exit, code, out + "" + err);
        assertTrue(out.toString().contains("\n" + verdict + ": "), out.toString());
        assertTrue(out.toString().contains("statistics: 1 " + verdict + " "), out.toString());
    }
}
