package io.dtron.bus.internal;

import java.io.DataInput;
import java.io.DataOutput;
import java.io.IOException;
import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.security.GeneralSecurityException;
import java.security.MessageDigest;
import javax.crypto.Mac;
import javax.crypto.spec.SecretKeySpec;
import org.jgroups.Address;
import org.jgroups.Message;
import org.jgroups.auth.AuthToken;
import org.jgroups.util.Bits;
import org.jgroups.util.UUID;

/**
 * Not API. A JGroups {@link AuthToken} proving knowledge of a shared secret
 * without sending it: the token carries HMAC-SHA256(secret, cluster name +
 * sender's address). The coordinator recomputes the code for the address the
 * join or merge request came from and admits the member only on a match.
 *
 * <p>Without encryption the code could be replayed by someone who records it
 * and fakes the same member address; turn encryption on where that matters.
 */
public final class SharedSecretToken extends AuthToken {
    private static final String ALGORITHM = "HmacSHA256";

    private final byte[] key;
    private final String clusterName;
    private byte[] receivedCode = new byte[0];

    /** Used by JGroups to read a token off the wire; such a token only carries a code. */
    public SharedSecretToken() {
        this(new byte[0], "");
    }

    SharedSecretToken(String secret, String clusterName) {
        this(secret.getBytes(StandardCharsets.UTF_8), clusterName);
    }

    private SharedSecretToken(byte[] key, String clusterName) {
        this.key = key;
        this.clusterName = clusterName;
    }

    @Override
    public String getName() {
        return SharedSecretToken.class.getName();
    }

    @Override
    public boolean authenticate(AuthToken token, Message msg) {
        if (!(token instanceof SharedSecretToken remote) || msg.getSrc() == null) {
            return false;
        }
        return MessageDigest.isEqual(code(msg.getSrc()), remote.receivedCode);
    }

    @Override
    public int size() {
        return Integer.BYTES + 32;
    }

    @Override
    public void writeTo(DataOutput out) throws IOException {
        byte[] code = code(auth.getAddress());
        Bits.writeIntCompressed(code.length, out);
        out.write(code);
    }

    @Override
    public void readFrom(DataInput in) throws IOException {
        int length = Bits.readIntCompressed(in);
        if (length < 0 || length > 64) {
            throw new IOException("invalid authentication code length " + length);
        }
        receivedCode = new byte[length];
        in.readFully(receivedCode);
    }

    /** The member's identity: the bits of its UUID, which stay the same whatever extensions the address carries. */
    private static byte[] identity(Address member) {
        if (member instanceof UUID uuid) {
            return ByteBuffer.allocate(16)
                    .putLong(uuid.getMostSignificantBits())
                    .putLong(uuid.getLeastSignificantBits())
                    .array();
        }
        return member.toString().getBytes(StandardCharsets.UTF_8);
    }

    private byte[] code(Address member) {
        try {
            Mac mac = Mac.getInstance(ALGORITHM);
            mac.init(new SecretKeySpec(key, ALGORITHM));
            mac.update(clusterName.getBytes(StandardCharsets.UTF_8));
            mac.update((byte) 0);
            mac.update(identity(member));
            return mac.doFinal();
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("cannot compute the authentication code", e);
        }
    }
}
