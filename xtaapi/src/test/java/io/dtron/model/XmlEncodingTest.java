package io.dtron.model;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.xta.Diagnostic;
import java.io.IOException;
import java.nio.charset.Charset;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * Model files in every encoding XML allows load from disk, as the Uppaal editor and other tools save them: UTF-8
 * with and without a byte-order mark, UTF-16 in both byte orders with their mark (and without one, told by the
 * first bytes), UTF-32, and encodings named in the XML declaration; errors keep their lines and columns. A
 * DOCTYPE's external entity is never read.
 */
class XmlEncodingTest {
    @TempDir
    Path dir;

    /** A valid model with characters beyond ASCII in a comment; {@code declaration} is its XML declaration. */
    private static String model(String declaration, String guard) {
        return declaration + """
                <nta>
                <declaration>// Température du four: ° and ü
                clock x; int i;</declaration>
                <template><name>Oven</name>
                <location id="a"><name>Heat</name></location>
                <location id="b"><name>Cool</name></location>
                <init ref="a"/>
                <transition><source ref="a"/><target ref="b"/><label kind="guard">GUARD</label></transition>
                </template>
                <system>system Oven;</system>
                </nta>
                """.replace("GUARD", guard);
    }

    private Path save(String name, byte[] bom, String text, Charset charset) throws IOException {
        byte[] body = text.getBytes(charset);
        byte[] bytes = new byte[bom.length + body.length];
        System.arraycopy(bom, 0, bytes, 0, bom.length);
        System.arraycopy(body, 0, bytes, bom.length, body.length);
        Path file = dir.resolve(name);
        Files.write(file, bytes);
        return file;
    }

    private static byte[] bytes(int... values) {
        byte[] b = new byte[values.length];
        for (int i = 0; i < values.length; i++) {
            b[i] = (byte) values[i];
        }
        return b;
    }

    private List<Path> everyEncoding(String guard) throws IOException {
        String utf8 = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n";
        String utf16 = "<?xml version=\"1.0\" encoding=\"utf-16\"?>\n";
        return List.of(
                save("utf8.xml", new byte[0], model(utf8, guard), StandardCharsets.UTF_8),
                save("utf8-bom.xml", bytes(0xEF, 0xBB, 0xBF), model(utf8, guard), StandardCharsets.UTF_8),
                save("utf16le-bom.xml", bytes(0xFF, 0xFE), model(utf16, guard), StandardCharsets.UTF_16LE),
                save("utf16be-bom.xml", bytes(0xFE, 0xFF), model(utf16, guard), StandardCharsets.UTF_16BE),
                save("utf16le.xml", new byte[0], model(utf16, guard), StandardCharsets.UTF_16LE),
                save("utf32le-bom.xml", bytes(0xFF, 0xFE, 0x00, 0x00), model("<?xml version=\"1.0\" encoding=\"UTF-32\"?>\n",
                        guard), Charset.forName("UTF-32LE")),
                save("latin1.xml", new byte[0], model("<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>\n", guard),
                        StandardCharsets.ISO_8859_1),
                save("cp1252.xml", new byte[0], model("<?xml version='1.0' encoding='windows-1252'?>\n", guard),
                        Charset.forName("windows-1252")));
    }

    @Test
    void aValidModelLoadsInEveryEncoding() throws IOException, ModelException {
        for (Path file : everyEncoding("x &gt; 2 &amp;&amp; i == 0")) {
            Network n = ModelLoader.load(file);
            assertEquals(List.of("Oven"), n.processes().stream().map(Process::name).toList(), file::toString);
            assertEquals(List.of("Heat", "Cool"), n.processes().get(0).locations().stream().map(Location::name)
                    .toList(), file::toString);
            assertEquals(1, n.clockCount(), file::toString);
            assertTrue(n.warnings().isEmpty(), () -> file + ": " + n.warnings());
        }
    }

    @Test
    void errorsKeepTheirPlaceInEveryEncoding() throws IOException {
        // the guard is on line 9 of every file (the XML declaration is line 1); 'missing' starts at column 85 of the
        // file and column 11 of the label
        for (Path file : everyEncoding("i == 0 &amp;&amp; missing &gt; 1")) {
            ModelException e = assertThrows(ModelException.class, () -> ModelLoader.load(file), file::toString);
            Diagnostic d = e.errors().get(0);
            assertEquals(file + ":9:85: error: unknown name 'missing' (template Oven, guard label, column 11)",
                    d.format());
        }
    }

    @Test
    void aDoctypeWithAnExternalEntityIsNeverRead() throws IOException {
        Path secret = dir.resolve("secret.txt");
        Files.writeString(secret, "int leaked;");
        String text = "<?xml version=\"1.0\" encoding=\"utf-16\"?>\n<!DOCTYPE nta [\n<!ENTITY ext SYSTEM \""
                + secret.toUri() + "\">\n]>\n<nta><declaration>&ext;</declaration><system>system;</system></nta>\n";
        Path file = save("entity.xml", bytes(0xFF, 0xFE), text, StandardCharsets.UTF_16LE);
        ModelException e = assertThrows(ModelException.class, () -> ModelLoader.load(file));
        Diagnostic d = e.errors().get(0);
        assertEquals(5, d.line(), d::format);
        assertTrue(d.message().startsWith("the entity '&ext;' is declared in the DOCTYPE, but DTRON reads no DTD"),
                d::format);
        assertFalse(e.getMessage().contains("leaked"), e::getMessage);
    }
}
